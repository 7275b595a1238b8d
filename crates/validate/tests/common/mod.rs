//! What the cases of tests/validate share: the options a case's `args.txt` asks for.

use std::path::Path;

use tidepack_loader::loader::Loader;
use tidepack_loader::macros::StandardMacros;
use tidepack_validate::{Options, Profiles};

/// The options of the case in `dir`: two threads, and what its `args.txt` names, `--profile
/// NAME` and `--loader NAME` (the loader's standard macros with it).
pub fn case_options(dir: &Path) -> Options {
    let args = std::fs::read_to_string(dir.join("args.txt")).unwrap_or_default();
    let mut options = Options { threads: 2, ..Options::default() };
    let words: Vec<&str> = args.split_whitespace().collect();
    for pair in words.chunks(2) {
        match pair {
            ["--profile", name] => options.profiles = Profiles::Named(name.to_string()),
            ["--loader", name] => {
                let loader: Loader = name.parse().unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
                options.loader = loader;
                options.macros = StandardMacros::for_loader(loader);
            }
            other => panic!("{}: unsupported args {other:?}", dir.display()),
        }
    }
    options
}
