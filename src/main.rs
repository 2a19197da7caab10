//! The `berry-evolve` command: parses the command line and reports errors as a cause chain.

fn main() {
    println!("berry-evolve {}", env!("CARGO_PKG_VERSION"));
}
