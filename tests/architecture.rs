//! The shape of the house, checked on the source itself (`cargo test --test architecture`):
//!
//! - the rooms `run/`, `post/`, `io/`, `solver/` and `linalg/` depend on each other one way only,
//!   in that order from the top (`run` may use every other, `linalg` none of them), and the
//!   foundation modules (scene, mesh, material, element, seismic, point, tensor, input, plot)
//!   use none of the five; an arrow is any `crate::ROOM` path in the code or in a doc link;
//! - no circle among the files of `linalg/`;
//! - no function in `src/` longer than 100 lines and no source file longer than 1,200 lines,
//!   tests aside;
//! - one definition of the FFI `call!` macro, and no `as` cast to or from `usize` or
//!   `PetscInt` in `linalg/` (conversions there are checked).
//!
//! `cfrd::architecture` draws the same map for readers.

use proc_macro2::Span;
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use syn::spanned::Spanned;
use syn::visit::Visit;

/// The rooms, top first: a room may use the rooms after it.
const ROOMS: [&str; 5] = ["run", "post", "io", "solver", "linalg"];
/// Modules below every room.
const FOUNDATION: [&str; 9] = [
    "scene", "mesh", "material", "element", "seismic", "point", "tensor", "input", "plot",
];
const MAX_FN_LINES: usize = 100;
const MAX_FILE_LINES: usize = 1200;

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("read src") {
        let path = entry.expect("dir entry").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The source files with their module paths relative to `src/` (`solver/newton.rs`).
fn sources() -> Vec<(String, String)> {
    let mut files = Vec::new();
    rust_files(&src(), &mut files);
    files.sort();
    files
        .into_iter()
        .map(|p| {
            let rel = p
                .strip_prefix(src())
                .unwrap()
                .to_string_lossy()
                .replace('\\', "/");
            (rel, std::fs::read_to_string(&p).expect("read source"))
        })
        .collect()
}

fn is_test_file(rel: &str) -> bool {
    let name = rel.rsplit('/').next().unwrap();
    name == "tests.rs" || name.ends_with("_tests.rs") || name == "test_support.rs"
}

fn is_cfg_test(attrs: &[syn::Attribute]) -> bool {
    attrs
        .iter()
        .any(|a| a.path().is_ident("cfg") && quote_tokens(&a.meta).replace(' ', "").contains("(test)"))
}

fn quote_tokens(t: &impl quote::ToTokens) -> String {
    t.to_token_stream().to_string()
}

/// What one file says: the `crate::` paths it uses (first segments after `crate`, with the
/// rest), its long functions and its lines outside tests.
#[derive(Default)]
struct Scan {
    uses: BTreeSet<Vec<String>>,
    long_fns: Vec<(String, usize)>,
    test_lines: usize,
    call_macros: usize,
    casts: Vec<(usize, String)>,
}

impl Scan {
    fn fn_len(&mut self, name: String, start: Span, end: Span) {
        let n = end.end().line + 1 - start.start().line;
        if n > MAX_FN_LINES {
            self.long_fns.push((name, n));
        }
    }

    /// Keeps the paths that name a module of the crate: `crate::`, `cfrd::`, `super::` and
    /// `self::` ones (resolved later against the file's own module).
    fn path_segments(&mut self, segs: Vec<String>) {
        let first = segs.first().map(String::as_str);
        if matches!(first, Some("crate" | "cfrd" | "super" | "self")) && segs.len() > 1 {
            self.uses.insert(segs);
        }
    }
}

impl<'ast> Visit<'ast> for Scan {
    fn visit_item_mod(&mut self, m: &'ast syn::ItemMod) {
        if is_cfg_test(&m.attrs) {
            let span = m.span();
            self.test_lines += span.end().line + 1 - span.start().line;
            return;
        }
        syn::visit::visit_item_mod(self, m);
    }

    fn visit_item_fn(&mut self, f: &'ast syn::ItemFn) {
        if is_cfg_test(&f.attrs) {
            return;
        }
        self.fn_len(
            f.sig.ident.to_string(),
            f.sig.fn_token.span,
            f.block.brace_token.span.close(),
        );
        syn::visit::visit_item_fn(self, f);
    }

    fn visit_impl_item_fn(&mut self, f: &'ast syn::ImplItemFn) {
        self.fn_len(
            f.sig.ident.to_string(),
            f.sig.fn_token.span,
            f.block.brace_token.span.close(),
        );
        syn::visit::visit_impl_item_fn(self, f);
    }

    fn visit_trait_item_fn(&mut self, f: &'ast syn::TraitItemFn) {
        if let Some(b) = &f.default {
            self.fn_len(
                f.sig.ident.to_string(),
                f.sig.fn_token.span,
                b.brace_token.span.close(),
            );
        }
        syn::visit::visit_trait_item_fn(self, f);
    }

    fn visit_item_macro(&mut self, m: &'ast syn::ItemMacro) {
        if m.mac.path.is_ident("macro_rules") && m.ident.as_ref().is_some_and(|i| i == "call") {
            self.call_macros += 1;
        }
        syn::visit::visit_item_macro(self, m);
    }

    fn visit_path(&mut self, p: &'ast syn::Path) {
        self.path_segments(p.segments.iter().map(|s| s.ident.to_string()).collect());
        syn::visit::visit_path(self, p);
    }

    fn visit_use_tree(&mut self, t: &'ast syn::UseTree) {
        let mut leaves = Vec::new();
        use_paths(t, Vec::new(), &mut leaves);
        for l in leaves {
            self.path_segments(l);
        }
    }

    fn visit_expr_cast(&mut self, c: &'ast syn::ExprCast) {
        let ty = quote_tokens(&c.ty).replace(' ', "");
        if ty == "usize" || ty.ends_with("PetscInt") {
            self.casts.push((c.span().start().line, format!("as {ty}")));
        }
        syn::visit::visit_expr_cast(self, c);
    }

    fn visit_attribute(&mut self, a: &'ast syn::Attribute) {
        // doc links: [`crate::post::profiles`] and the like
        if let syn::Meta::NameValue(nv) = &a.meta {
            if nv.path.is_ident("doc") {
                let text = quote_tokens(&nv.value);
                for word in text.split(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':')) {
                    let segs: Vec<String> = word.split("::").map(str::to_string).collect();
                    self.path_segments(segs);
                }
            }
        }
    }
}

/// The whole paths a `use` tree names (groups expanded, `self` and globs cut).
fn use_paths(t: &syn::UseTree, prefix: Vec<String>, out: &mut Vec<Vec<String>>) {
    let with = |s: String| {
        let mut p = prefix.clone();
        p.push(s);
        p
    };
    match t {
        syn::UseTree::Path(p) => use_paths(&p.tree, with(p.ident.to_string()), out),
        syn::UseTree::Name(n) if n.ident == "self" => out.push(prefix),
        syn::UseTree::Name(n) => out.push(with(n.ident.to_string())),
        syn::UseTree::Rename(r) => out.push(with(r.ident.to_string())),
        syn::UseTree::Glob(_) => out.push(prefix),
        syn::UseTree::Group(g) => g.items.iter().for_each(|i| use_paths(i, prefix.clone(), out)),
    }
}

fn scan(rel: &str, text: &str) -> Scan {
    let file = syn::parse_file(text).unwrap_or_else(|e| panic!("src/{rel}: {e}"));
    let mut s = Scan::default();
    s.visit_file(&file);
    s
}

/// The room (or foundation module) of a file, by its first directory or file stem.
fn module_of(rel: &str) -> String {
    rel.split('/').next().unwrap().trim_end_matches(".rs").to_string()
}

/// The module path of a file: `solver/newton.rs` is `[solver, newton]`, `run/mod.rs` is `[run]`.
fn module_path(rel: &str) -> Vec<String> {
    let mut m: Vec<String> = rel
        .trim_end_matches(".rs")
        .split('/')
        .map(str::to_string)
        .collect();
    if m.last().is_some_and(|l| l == "mod" || l == "lib" || l == "main") {
        m.pop();
    }
    m
}

/// A path as seen from the file `rel`, made absolute (without `crate`).
fn resolve(rel: &str, path: &[String]) -> Vec<String> {
    let mut base = module_path(rel);
    let mut rest = path;
    match path[0].as_str() {
        "crate" | "cfrd" => {
            base.clear();
            rest = &path[1..];
        }
        _ => {
            while let Some(first) = rest.first() {
                match first.as_str() {
                    "super" => {
                        base.pop();
                    }
                    "self" => {}
                    _ => break,
                }
                rest = &rest[1..];
            }
        }
    }
    base.extend(rest.iter().cloned());
    base
}

fn scans() -> Vec<(String, usize, Scan)> {
    sources()
        .into_iter()
        .map(|(rel, text)| {
            let mut s = scan(&rel, &text);
            s.uses = s
                .uses
                .iter()
                .map(|u| resolve(&rel, u))
                .filter(|u| !u.is_empty())
                .collect();
            (rel, text.lines().count(), s)
        })
        .collect()
}

#[test]
fn rooms_depend_one_way() {
    let rank = |m: &str| ROOMS.iter().position(|r| *r == m);
    let mut wrong = Vec::new();
    for (rel, _, s) in scans() {
        let from = module_of(&rel);
        for used in &s.uses {
            let to = used[0].as_str();
            if to == from {
                continue;
            }
            let back_up = match (rank(&from), rank(to)) {
                (Some(a), Some(b)) => b < a,
                (None, Some(_)) => FOUNDATION.contains(&from.as_str()),
                _ => false,
            };
            if back_up {
                wrong.push(format!("src/{rel} uses crate::{}", used.join("::")));
            }
        }
    }
    assert!(wrong.is_empty(), "arrows that run back up:\n{}", wrong.join("\n"));
}

/// The file of `crate::linalg::...` a path names: the longest prefix with a file.
fn linalg_file(path: &[String]) -> Option<String> {
    (1..=path.len()).rev().find_map(|n| {
        let p = path[..n].join("/");
        [format!("{p}.rs"), format!("{p}/mod.rs")]
            .into_iter()
            .find(|f| src().join(f).is_file())
    })
}

#[test]
fn no_circle_in_linalg() {
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (rel, _, s) in scans().into_iter().filter(|(r, _, _)| r.starts_with("linalg/")) {
        let to: BTreeSet<String> = s
            .uses
            .iter()
            .filter(|u| u[0] == "linalg")
            .filter_map(|u| linalg_file(u))
            .filter(|f| *f != rel && !f.ends_with("mod.rs"))
            .collect();
        graph.insert(rel, to);
    }
    fn visit(
        n: &str,
        g: &BTreeMap<String, BTreeSet<String>>,
        path: &mut Vec<String>,
        done: &mut BTreeSet<String>,
    ) {
        if let Some(i) = path.iter().position(|p| p == n) {
            panic!("circle in linalg/: {} -> {n}", path[i..].join(" -> "));
        }
        if !done.insert(n.to_string()) {
            return;
        }
        path.push(n.to_string());
        for m in g.get(n).into_iter().flatten() {
            visit(m, g, path, done);
        }
        path.pop();
    }
    let mut done = BTreeSet::new();
    for n in graph.keys() {
        visit(n, &graph, &mut Vec::new(), &mut done);
    }
}

#[test]
fn functions_and_files_are_short() {
    let mut long = Vec::new();
    for (rel, lines, s) in scans().into_iter().filter(|(r, _, _)| !is_test_file(r)) {
        for (name, n) in &s.long_fns {
            long.push(format!(
                "src/{rel}: fn {name}, {n} lines (at most {MAX_FN_LINES})"
            ));
        }
        let code = lines - s.test_lines;
        if code > MAX_FILE_LINES {
            long.push(format!(
                "src/{rel}: {code} lines outside tests (at most {MAX_FILE_LINES})"
            ));
        }
    }
    assert!(long.is_empty(), "too long:\n{}", long.join("\n"));
}

#[test]
fn ffi_calls_go_through_one_checked_layer() {
    let all = scans();
    let macros: usize = all.iter().map(|(_, _, s)| s.call_macros).sum();
    assert_eq!(macros, 1, "definitions of the `call!` macro in src/");
    let casts: Vec<String> = all
        .iter()
        .filter(|(r, _, _)| r.starts_with("linalg/") && !is_test_file(r))
        .flat_map(|(r, _, s)| s.casts.iter().map(move |(l, c)| format!("src/{r}:{l}: {c}")))
        .collect();
    assert!(
        casts.is_empty(),
        "unchecked casts in linalg/:\n{}",
        casts.join("\n")
    );
}
