//! `tools/test`, the README's test command, on simulated machines: PATH shims stand in for
//! dpkg-query (which knows only the packages a case installs), apt-get, apt-cache, tee, sudo and
//! cargo (which record their calls), and glslangValidator is absent unless a case installs it.
//! The script must ask apt-get for every package the tests need and reach `cargo test`, or stop
//! with a message that says why; a silent non-zero exit is a failure.

use std::fs;
use std::os::unix::fs::{PermissionsExt, symlink};
use std::path::{Path, PathBuf};
use std::process::Command;

const SHIMMED: &[&str] = &["glslangValidator", "dpkg-query", "apt-get", "apt-cache", "tee", "sudo", "cargo", "rustup"];

struct Machine {
    /// Installed Debian packages with their versions.
    installed: Vec<(&'static str, &'static str)>,
    /// What `apt-cache policy mesa-vulkan-drivers` offers.
    mesa_candidate: &'static str,
    /// VERSION_CODENAME of the simulated os-release.
    codename: &'static str,
    /// Whether apt-get fails (a broken mirror, no network).
    apt_fails: bool,
}

struct Outcome {
    status: i32,
    output: String,
    /// One line per recorded call of apt-get and cargo.
    calls: Vec<String>,
    /// What the script wrote through tee (the backports source list).
    teed: String,
}

fn write_script(path: &Path, body: &str) {
    fs::write(path, format!("#!/bin/sh\n{body}\n")).unwrap();
    fs::set_permissions(path, fs::Permissions::from_mode(0o755)).unwrap();
}

fn run_tools_test(machine: &Machine, args: &[&str]) -> Outcome {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let work = tempfile::tempdir().unwrap();
    let bin = work.path().join("bin");
    fs::create_dir(&bin).unwrap();
    for dir in ["/usr/local/bin", "/usr/bin", "/bin"] {
        let Ok(entries) = fs::read_dir(dir) else { continue };
        for entry in entries.flatten() {
            let name = entry.file_name();
            let target = bin.join(&name);
            if SHIMMED.iter().any(|s| name == **s) || target.symlink_metadata().is_ok() {
                continue;
            }
            symlink(entry.path(), &target).unwrap();
        }
    }
    let log: PathBuf = work.path().join("calls.log");
    let tee_log = work.path().join("tee.log");
    let mut known = String::new();
    for (package, version) in &machine.installed {
        known += &format!("  {package}) printf 'install ok installed {version}'; exit 0;;\n");
    }
    write_script(
        &bin.join("dpkg-query"),
        &format!(
            "for last; do :; done\ncase \"$last\" in\n{known}esac\necho \"dpkg-query: no packages found matching $last\" >&2\nexit 1"
        ),
    );
    if machine.installed.iter().any(|(p, _)| *p == "glslang-tools") {
        write_script(&bin.join("glslangValidator"), "exit 0");
    }
    let apt_status = if machine.apt_fails { "echo 'E: Unable to fetch some archives' >&2; exit 100" } else { "exit 0" };
    write_script(&bin.join("apt-get"), &format!("echo \"apt-get $*\" >> '{}'\n{apt_status}", log.display()));
    write_script(
        &bin.join("apt-cache"),
        &format!(
            "case \"$*\" in *policy*) echo \"$2:\"; echo '  Installed: (none)'; echo '  Candidate: {}';; esac\nexit 0",
            machine.mesa_candidate
        ),
    );
    write_script(&bin.join("tee"), &format!("cat >> '{}'", tee_log.display()));
    write_script(&bin.join("sudo"), "exec \"$@\"");
    write_script(&bin.join("cargo"), &format!("echo \"cargo $*\" >> '{}'\nexit 0", log.display()));
    let os_release = work.path().join("os-release");
    fs::write(&os_release, format!("ID=debian\nVERSION_CODENAME={}\n", machine.codename)).unwrap();

    let out = Command::new("/bin/bash")
        .arg(root.join("tools/test"))
        .args(args)
        .env_clear()
        .env("PATH", &bin)
        .env("HOME", work.path())
        .env("TIDEPACK_OS_RELEASE", &os_release)
        .output()
        .unwrap();
    Outcome {
        status: out.status.code().unwrap_or(-1),
        output: String::from_utf8_lossy(&out.stdout).into_owned() + &String::from_utf8_lossy(&out.stderr),
        calls: fs::read_to_string(&log).unwrap_or_default().lines().map(str::to_owned).collect(),
        teed: fs::read_to_string(&tee_log).unwrap_or_default(),
    }
}

/// The packages named by the apt-get install calls.
fn installed_by(outcome: &Outcome) -> Vec<String> {
    let mut packages: Vec<String> = outcome
        .calls
        .iter()
        .filter(|c| c.starts_with("apt-get ") && c.contains(" install "))
        .flat_map(|c| c.split_whitespace().filter(|w| !w.starts_with('-') && !["apt-get", "install", "bookworm-backports"].contains(w)))
        .map(str::to_owned)
        .collect();
    packages.sort();
    packages.dedup();
    packages
}

fn reached_cargo_test(outcome: &Outcome) -> bool {
    outcome.calls.iter().any(|c| c.starts_with("cargo test --workspace --locked"))
}

const ALL_PACKAGES: [&str; 5] = ["glslang-tools", "libegl-mesa0", "libegl1", "libgl1-mesa-dri", "mesa-vulkan-drivers"];

#[test]
fn fresh_debian_12_installs_everything_from_backports_then_tests() {
    let outcome =
        run_tools_test(&Machine { installed: vec![], mesa_candidate: "22.3.6-1+deb12u1", codename: "bookworm", apt_fails: false }, &[]);
    assert_eq!(outcome.status, 0, "{}", outcome.output);
    assert_eq!(installed_by(&outcome), ALL_PACKAGES, "{:?}", outcome.calls);
    assert!(outcome.teed.contains("bookworm-backports main"), "backports source not added: {:?}", outcome.teed);
    let mesa_install = outcome.calls.iter().find(|c| c.contains("mesa-vulkan-drivers")).unwrap();
    assert!(mesa_install.contains("-t bookworm-backports"), "{mesa_install}");
    assert!(reached_cargo_test(&outcome), "{:?}", outcome.calls);
}

#[test]
fn fresh_machine_with_mesa_25_candidate_installs_it_without_backports() {
    let outcome =
        run_tools_test(&Machine { installed: vec![], mesa_candidate: "25.0.7-2", codename: "trixie", apt_fails: false }, &[]);
    assert_eq!(outcome.status, 0, "{}", outcome.output);
    assert_eq!(installed_by(&outcome), ALL_PACKAGES, "{:?}", outcome.calls);
    assert!(outcome.teed.is_empty(), "no extra apt source is needed: {}", outcome.teed);
    assert!(reached_cargo_test(&outcome));
}

#[test]
fn ready_machine_goes_straight_to_cargo_test_with_the_extra_arguments() {
    let outcome = run_tools_test(
        &Machine {
            installed: vec![
                ("glslang-tools", "12.0.0-2"),
                ("libegl1", "1.6.0-1"),
                ("mesa-vulkan-drivers", "25.0.7-2~bpo12+1"),
                ("libegl-mesa0", "25.0.7-2~bpo12+1"),
                ("libgl1-mesa-dri", "25.0.7-2~bpo12+1"),
            ],
            mesa_candidate: "25.0.7-2~bpo12+1",
            codename: "bookworm",
            apt_fails: false,
        },
        &["-p", "tidepack-glsl"],
    );
    assert_eq!(outcome.status, 0, "{}", outcome.output);
    assert_eq!(outcome.calls, ["cargo test --workspace --locked -p tidepack-glsl"]);
}

#[test]
fn old_mesa_is_upgraded() {
    let outcome = run_tools_test(
        &Machine {
            installed: vec![
                ("glslang-tools", "12.0.0-2"),
                ("libegl1", "1.6.0-1"),
                ("mesa-vulkan-drivers", "22.3.6-1+deb12u1"),
                ("libegl-mesa0", "22.3.6-1+deb12u1"),
                ("libgl1-mesa-dri", "22.3.6-1+deb12u1"),
            ],
            mesa_candidate: "22.3.6-1+deb12u1",
            codename: "bookworm",
            apt_fails: false,
        },
        &[],
    );
    assert_eq!(outcome.status, 0, "{}", outcome.output);
    assert_eq!(installed_by(&outcome), ["libegl-mesa0", "libgl1-mesa-dri", "mesa-vulkan-drivers"]);
    assert!(reached_cargo_test(&outcome));
}

#[test]
fn no_mesa_25_anywhere_stops_with_a_reason() {
    let outcome =
        run_tools_test(&Machine { installed: vec![], mesa_candidate: "22.3.6-1", codename: "jammy", apt_fails: false }, &[]);
    assert_ne!(outcome.status, 0);
    assert!(outcome.output.contains("needs Mesa >= 25"), "{}", outcome.output);
    assert!(!reached_cargo_test(&outcome));
}

#[test]
fn a_failing_apt_get_is_named() {
    let outcome =
        run_tools_test(&Machine { installed: vec![], mesa_candidate: "25.0.7-2", codename: "trixie", apt_fails: true }, &[]);
    assert_ne!(outcome.status, 0);
    assert!(outcome.output.contains("tools/test: failed"), "silent failure: {}", outcome.output);
    assert!(outcome.output.contains("apt-get"), "{}", outcome.output);
    assert!(!reached_cargo_test(&outcome));
}
