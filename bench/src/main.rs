fn main() {
    println!("flexbody-bench: no suites yet");
}
