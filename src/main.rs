fn main() {
    println!("brume {}", env!("CARGO_PKG_VERSION"));
}
