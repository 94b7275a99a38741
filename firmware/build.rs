//! Picks the memory layout: a QEMU machine's or a Pico's (`firmware/memory/*.x`, by feature) or
//! the Black Pill rig's (`memory.x` at the workspace root), and passes the linker scripts.
//!
//! cortex-m-rt's `link.x` says `INCLUDE memory.x`. The selected layout is written as
//! `memory.x` into `OUT_DIR`, which goes first on the linker's search path.
use std::{env, fs, path::PathBuf};

fn main() {
    let manifest = PathBuf::from(env::var_os("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"));
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    let layout = if env::var_os("CARGO_FEATURE_QEMU_MPS2_AN386").is_some() {
        manifest.join("memory/mps2-an386.x")
    } else if env::var_os("CARGO_FEATURE_QEMU_MICROBIT").is_some() {
        manifest.join("memory/microbit.x")
    } else if env::var_os("CARGO_FEATURE_QEMU_MPS2_AN505").is_some() {
        manifest.join("memory/mps2-an505.x")
    } else if env::var_os("CARGO_FEATURE_BOARD_PICO2").is_some() {
        manifest.join("memory/rp2350.x")
    } else if env::var_os("CARGO_FEATURE_BOARD_PICO").is_some() {
        manifest.join("memory/rp2040.x")
    } else {
        manifest.join("../memory.x")
    };
    fs::copy(&layout, out.join("memory.x")).expect("copy the memory layout into OUT_DIR");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed={}", layout.display());
    println!("cargo:rerun-if-changed=build.rs");
    // The build id sent in the link's Hello: the first 8 characters of the git commit (or
    // MS_BUILD_ID from the environment; "unknown" outside a git checkout).
    let id = env::var("MS_BUILD_ID").ok().or_else(|| {
        let out = std::process::Command::new("git")
            .args(["rev-parse", "--short=8", "HEAD"])
            .current_dir(&manifest)
            .output()
            .ok()?;
        out.status.success().then(|| String::from_utf8_lossy(&out.stdout).trim().to_owned())
    });
    println!("cargo:rustc-env=MS_BUILD_ID={}", id.unwrap_or_else(|| "unknown".into()));
    println!("cargo:rerun-if-env-changed=MS_BUILD_ID");
    for git in ["../.git/HEAD", "../.git/refs/heads"] {
        if manifest.join(git).exists() {
            println!("cargo:rerun-if-changed={}", manifest.join(git).display());
        }
    }
    let target = env::var("TARGET").unwrap_or_default();
    // The Cortex-M0's f32 multiplication and addition (src/soft_float.rs), where compiler_builtins' is used:
    // not on the Pico's default build, whose floats come from the boot ROM.
    println!("cargo::rustc-check-cfg=cfg(soft_float)");
    let rom_floats = env::var_os("CARGO_FEATURE_BOARD_PICO").is_some()
        && env::var_os("CARGO_FEATURE_BUILTINS_FLOAT").is_none();
    if target.starts_with("thumbv6m") && !rom_floats {
        println!("cargo:rustc-cfg=soft_float");
    }
    // A rig of both scenes, the meter stick's and the stack's, switched by the host
    // (src/realtime_stack.rs, `run_both_scenes`): the Picos with the link.
    println!("cargo::rustc-check-cfg=cfg(both_scenes)");
    let pico = env::var_os("CARGO_FEATURE_BOARD_PICO").is_some()
        || env::var_os("CARGO_FEATURE_BOARD_PICO2").is_some();
    if pico && env::var_os("CARGO_FEATURE_LINK").is_some() {
        println!("cargo:rustc-cfg=both_scenes");
    }
    if target.starts_with("thumb") {
        println!("cargo:rustc-link-arg-bins=-Tlink.x");
        if env::var_os("CARGO_FEATURE_LOG").is_some() {
            println!("cargo:rustc-link-arg-bins=-Tdefmt.x");
        }
    }
}
