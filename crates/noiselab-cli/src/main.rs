//! `noiselab`: sample and render procedural noise from the command line.

fn main() -> std::process::ExitCode {
    noiselab_cli::run()
}
