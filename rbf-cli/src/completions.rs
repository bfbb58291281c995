//! `rbf completions`: shell completion scripts.

use clap::CommandFactory;
use clap_complete::Shell;

/// Prints the completion script for `shell` on stdout.
pub(crate) fn run<C: CommandFactory>(shell: Shell) {
    let mut command = C::command();
    clap_complete::generate(shell, &mut command, "rbf", &mut std::io::stdout());
}
