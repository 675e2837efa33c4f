//! The `cfrd` command line.

fn main() {
    println!("cfrd {}", env!("CARGO_PKG_VERSION"));
}
