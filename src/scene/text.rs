//! Checks of the scene text before it is parsed into a [`super::SceneFile`]: a leading UTF-8 byte
//! order mark is dropped, nesting deeper than a documented limit is refused before the YAML parser
//! sees it, and a key given twice in one mapping (which the typed parse would silently resolve
//! to the last value) is an error naming both lines.

use super::error::SceneError;

/// Deepest flow nesting accepted: at most this many `[` or `{` open at once.
pub const MAX_FLOW_DEPTH: usize = 64;
/// Deepest block nesting accepted, as columns of indentation (spaces and `- `/`? ` indicators
/// before a line's content): 256 columns, some 100 levels at two spaces.
pub const MAX_BLOCK_INDENT: usize = 256;

/// The scene text without a leading UTF-8 byte order mark.
pub fn strip_bom(text: &str) -> &str {
    text.strip_prefix('\u{feff}').unwrap_or(text)
}

/// Refuses text nested deeper than [`MAX_FLOW_DEPTH`] or [`MAX_BLOCK_INDENT`], naming the line.
/// Quoted scalars and comments are skipped; the check is linear in the text length.
pub fn check_depth(text: &str, source: &str) -> Result<(), SceneError> {
    let mut depth = 0usize;
    let mut quote: Option<char> = None;
    for (n, line) in text.lines().enumerate() {
        let too_deep = |message: String| SceneError::Parse {
            file: source.to_string(),
            path: "(document)".into(),
            message: format!("line {}: {message}", n + 1),
        };
        if quote.is_none() && depth == 0 {
            let indent = block_indent(line);
            if indent > MAX_BLOCK_INDENT {
                return Err(too_deep(format!(
                    "indented by {indent} columns, more than the limit of {MAX_BLOCK_INDENT}"
                )));
            }
        }
        let mut prev = ' ';
        for c in line.chars() {
            match (quote, c) {
                (Some(q), c) if c == q => quote = None,
                (Some(_), _) => {}
                (None, '#') if prev.is_whitespace() => break,
                (None, '"' | '\'') if depth > 0 || prev.is_whitespace() || prev == ':' => quote = Some(c),
                (None, '[' | '{') => {
                    depth += 1;
                    if depth > MAX_FLOW_DEPTH {
                        return Err(too_deep(format!(
                            "brackets nested more than {MAX_FLOW_DEPTH} deep"
                        )));
                    }
                }
                (None, ']' | '}') => depth = depth.saturating_sub(1),
                _ => {}
            }
            prev = c;
        }
        if depth == 0 {
            // a quoted scalar continued on the next lines is read as plain text there: only
            // unbalanced brackets in it could count, and they would have to be many
            quote = None;
        }
    }
    Ok(())
}

/// Columns of indentation of `line`: leading spaces and tabs, and `- `/`? ` indicators.
fn block_indent(line: &str) -> usize {
    let b = line.as_bytes();
    let mut i = 0;
    while i < b.len() {
        match b[i] {
            b' ' | b'\t' => i += 1,
            b'-' | b'?' if b.get(i + 1).is_some_and(|c| *c == b' ') => i += 2,
            _ => break,
        }
    }
    i
}

/// Refuses a key given twice in one mapping anywhere in the document (e.g. a block or material
/// named twice), naming the mapping's YAML path and both lines. Other YAML errors are left to
/// the typed parse, which reports them with their path.
pub fn check_duplicate_keys(text: &str, source: &str) -> Result<(), SceneError> {
    let de = serde_yaml::Deserializer::from_str(text);
    let Err(e) = serde_path_to_error::deserialize::<_, serde_yaml::Value>(de) else {
        return Ok(());
    };
    let path = match e.path().to_string() {
        p if p == "?" || p == "." => "(document)".to_string(),
        p => p,
    };
    let inner = e.into_inner();
    let message = inner.to_string();
    let Some(key) = duplicate_key(&message) else {
        return Ok(());
    };
    let from = inner.location().map_or(1, |l| l.line());
    let lines = key_lines(text, from, &key);
    let message = match lines.as_slice() {
        [a, b, ..] => format!(
            "the key '{key}' is given twice, on lines {a} and {b}; YAML would keep only the \
             last one: remove or rename one of them"
        ),
        _ => format!(
            "the key '{key}' is given twice in the mapping that starts on line {from}; remove or \
             rename one of them"
        ),
    };
    Err(SceneError::Parse {
        file: source.to_string(),
        path,
        message,
    })
}

/// The key of serde_yaml's "duplicate entry with key ..." message.
fn duplicate_key(message: &str) -> Option<String> {
    let marker = "duplicate entry with key ";
    let rest = &message[message.find(marker)? + marker.len()..];
    let rest = rest.split(" at line ").next().unwrap_or(rest);
    let key = match rest.strip_prefix('"') {
        Some(quoted) => serde_json::from_str::<String>(&format!("\"{quoted}")).ok()?,
        None => rest.trim_matches('`').to_string(),
    };
    Some(key)
}

/// 1-based numbers of the lines from `from` on where `key` is written as a mapping key (plain,
/// single- or double-quoted): at the start of a line's content at the first such column, or
/// after `{` or `,` in flow style.
fn key_lines(text: &str, from: usize, key: &str) -> Vec<usize> {
    let forms = [key.to_string(), format!("\"{key}\""), format!("'{key}'")];
    let mut column = None;
    let mut out = Vec::new();
    for (n, line) in text.lines().enumerate().skip(from.saturating_sub(1)) {
        for form in &forms {
            for (at, _) in line.match_indices(form.as_str()) {
                let after = line[at + form.len()..].trim_start();
                if !after.starts_with(':') {
                    continue;
                }
                let before = line[..at].trim_end();
                let block = block_indent(line) == at;
                let flow = before.ends_with('{') || before.ends_with(',');
                if (block && *column.get_or_insert(at) == at) || flow {
                    out.push(n + 1);
                }
            }
        }
        if out.len() >= 2 {
            break;
        }
    }
    out.dedup();
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn deep_flow_nesting_is_refused_quickly() {
        let text = format!("name: {}", "[".repeat(100_000));
        let t = std::time::Instant::now();
        let msg = check_depth(&text, "deep.yaml").expect_err("too deep").to_string();
        assert!(t.elapsed().as_secs_f64() < 1.0);
        assert!(
            msg.contains("deep.yaml") && msg.contains("line 1") && msg.contains("64"),
            "{msg}"
        );
        let text = format!("a:\n{}x: 1\n", " ".repeat(300));
        let msg = check_depth(&text, "indent.yaml")
            .expect_err("too deep")
            .to_string();
        assert!(msg.contains("line 2") && msg.contains("300 columns"), "{msg}");
        let text = format!(
            "a: {}1{}\nb: '[[[[' # {}\n",
            "[".repeat(60),
            "]".repeat(60),
            "{".repeat(99)
        );
        check_depth(&text, "ok.yaml").expect("within the limit");
    }

    #[test]
    fn a_duplicate_key_names_both_lines_in_block_and_flow_style() {
        let text =
            "name: t\nblocks:\n  core: { material: a }\n  shell: { material: b }\n  core: { material: b }\n";
        let msg = check_duplicate_keys(text, "d.yaml")
            .expect_err("duplicate")
            .to_string();
        assert!(msg.contains("d.yaml: blocks:") && msg.contains("'core'"), "{msg}");
        assert!(msg.contains("lines 3 and 5"), "{msg}");
        let text = "name: t\nmaterials: { soil: { young: 1 },\n  'soil': { young: 2 } }\n";
        let msg = check_duplicate_keys(text, "f.yaml")
            .expect_err("duplicate")
            .to_string();
        assert!(
            msg.contains("materials") && msg.contains("lines 2 and 3"),
            "{msg}"
        );
        check_duplicate_keys("a: { b: 1 }\nc: { b: 1 }\n", "ok.yaml").expect("no duplicate");
    }

    #[test]
    fn a_byte_order_mark_is_dropped() {
        assert_eq!(strip_bom("\u{feff}name: t"), "name: t");
        assert_eq!(strip_bom("name: t"), "name: t");
    }
}
