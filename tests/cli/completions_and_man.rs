//! `completions SHELL` and `man`: the scripts and the page name every subcommand, and the bash
//! script is valid bash.

use crate::cli_common::run_ok;

const SUBCOMMANDS: [&str; 6] = [
    "run",
    "resume",
    "export-csv",
    "inspect",
    "compare",
    "render",
];

#[test]
fn completions_name_every_subcommand_and_the_bash_script_parses() {
    for shell in ["bash", "zsh", "fish"] {
        let out = run_ok(&["completions", shell]);
        let script = String::from_utf8_lossy(&out.stdout);
        for name in SUBCOMMANDS {
            assert!(script.contains(name), "{shell} completions lack {name}");
        }
    }
    let out = run_ok(&["completions", "bash"]);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("berry-evolve.bash");
    std::fs::write(&path, &out.stdout).unwrap();
    let check = std::process::Command::new("bash")
        .arg("-n")
        .arg(&path)
        .output()
        .expect("bash runs");
    assert!(
        check.status.success(),
        "bash -n: {}",
        String::from_utf8_lossy(&check.stderr)
    );
}

#[test]
fn the_man_page_is_roff_with_every_subcommand() {
    let out = run_ok(&["man"]);
    let page = String::from_utf8_lossy(&out.stdout);
    assert!(page.contains(".TH berry-evolve 1"), "{page}");
    assert!(page.contains(".SH SYNOPSIS"), "{page}");
    for name in SUBCOMMANDS {
        assert!(
            page.contains(&name.replace('-', "\\-")),
            "the man page lacks {name}"
        );
    }
}

#[test]
fn an_unknown_shell_is_refused_with_the_ones_there_are() {
    let out = crate::cli_common::bin()
        .args(["completions", "tcsh"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        stderr.contains("bash") && stderr.contains("zsh"),
        "{stderr}"
    );
}
