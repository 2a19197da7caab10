//! The start-up CPU check (`src/cpu.rs`) on emulated CPUs: a build for x86-64-v3 must stop
//! with its message on a CPU without AVX, not die on an illegal instruction, and must run on
//! the oldest CPU it is built for.
//!
//! Needs `qemu-x86_64` (Debian's qemu-user). Without it the test says so and passes, unless
//! `BERRY_REQUIRE_QEMU` is set, as `.ci/run` sets it after installing qemu-user.

use std::process::{Command, Output};

fn under_qemu(cpu: &str, args: &[&str]) -> Option<Output> {
    match Command::new("qemu-x86_64")
        .args(["-cpu", cpu, env!("CARGO_BIN_EXE_berry-evolve")])
        .args(args)
        .output()
    {
        Ok(output) => Some(output),
        Err(e) if std::env::var_os("BERRY_REQUIRE_QEMU").is_some() => {
            panic!("BERRY_REQUIRE_QEMU is set but qemu-x86_64 did not start: {e}")
        }
        Err(e) => {
            eprintln!("skipped: qemu-x86_64 did not start ({e}); install qemu-user to run it");
            None
        }
    }
}

#[test]
fn an_older_cpu_gets_a_message_and_the_oldest_supported_one_runs() {
    if !cfg!(all(target_arch = "x86_64", target_feature = "avx2")) {
        eprintln!("skipped: this build does not use x86-64-v3 extensions");
        return;
    }
    // Nehalem (2008): SSE4.2, no AVX. Sandy Bridge (2011): AVX without AVX2, FMA or BMI.
    for old in ["Nehalem", "SandyBridge"] {
        let Some(out) = under_qemu(old, &["--version"]) else {
            return;
        };
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(
            out.status.code(),
            Some(1),
            "{old}: {:?}, stderr {stderr}",
            out.status
        );
        assert!(
            stderr.contains("instruction-set extensions that this CPU lacks")
                && stderr.contains("target-cpu=native"),
            "{old}: {stderr}"
        );
        assert!(out.stdout.is_empty(), "{old}: printed before the check");
    }
    // Haswell (2013) has all of x86-64-v3: a generation of evolution runs there and gives
    // the same bytes as on this machine.
    let dir = tempfile::tempdir().unwrap();
    let (here, haswell) = (dir.path().join("here"), dir.path().join("haswell"));
    let run = |out: &std::path::Path| {
        let out = out.to_str().unwrap().to_owned();
        [
            "run",
            "experiments/foraging.toml",
            "--generations",
            "1",
            "-q",
            "--out",
        ]
        .map(str::to_owned)
        .into_iter()
        .chain([out])
        .collect::<Vec<_>>()
    };
    let native = Command::new(env!("CARGO_BIN_EXE_berry-evolve"))
        .args(run(&here))
        .output()
        .unwrap();
    assert!(
        native.status.success(),
        "{}",
        String::from_utf8_lossy(&native.stderr)
    );
    let args = run(&haswell);
    let Some(out) = under_qemu(
        "Haswell",
        &args.iter().map(String::as_str).collect::<Vec<_>>(),
    ) else {
        return;
    };
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for file in ["fitness.csv", "best.json"] {
        let (a, b) = (here.join(file), haswell.join(file));
        assert_eq!(
            std::fs::read(&a).unwrap(),
            std::fs::read(&b).unwrap(),
            "{file}"
        );
    }
}
