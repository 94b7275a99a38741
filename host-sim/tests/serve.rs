//! `host-sim serve`: the binary serves a page folder on 127.0.0.1 (port 0: a free one, printed),
//! with content types, refusals of paths that leave it, the replay list; and refuses to start,
//! with a clear message, without the wasm module or with a folder that holds no run.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

fn page(name: &str, wasm: bool) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("meterstick-serve-cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("pkg")).unwrap();
    std::fs::write(dir.join("index.html"), "<!doctype html><title>t</title>").unwrap();
    std::fs::write(dir.join("app.js"), "export {};").unwrap();
    if wasm {
        std::fs::write(dir.join("pkg/meterstick_web.wasm"), b"\0asm\x01\0\0\0").unwrap();
    }
    dir
}

/// A raw GET: (status line, headers and body as text).
fn get(port: u16, path: &str) -> (String, String) {
    let mut s = TcpStream::connect(("127.0.0.1", port)).unwrap();
    write!(s, "GET {path} HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n").unwrap();
    let mut text = String::new();
    s.read_to_string(&mut text).unwrap();
    let status = text.lines().next().unwrap_or("").to_owned();
    (status, text)
}

/// A raw request: (headers as text, body bytes).
fn request(port: u16, method: &str, path: &str) -> (String, Vec<u8>) {
    let mut s = TcpStream::connect(("127.0.0.1", port)).unwrap();
    write!(s, "{method} {path} HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n").unwrap();
    let mut bytes = Vec::new();
    s.read_to_end(&mut bytes).unwrap();
    let end = bytes.windows(4).position(|w| w == b"\r\n\r\n").expect("a blank line after the headers");
    (String::from_utf8(bytes[..end].to_vec()).unwrap(), bytes[end + 4..].to_vec())
}

fn serve(args: &[&str]) -> (std::process::Child, u16) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .arg("serve")
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let mut line = String::new();
    BufReader::new(child.stdout.take().unwrap()).read_line(&mut line).unwrap();
    let port = line
        .split("http://127.0.0.1:")
        .nth(1)
        .and_then(|r| r.split('/').next())
        .and_then(|p| p.parse().ok())
        .unwrap_or_else(|| panic!("no address in {line:?}"));
    (child, port)
}

fn run_folder(dir: &Path) {
    std::fs::create_dir_all(dir.join("v0.5")).unwrap();
    for f in ["core.csv", "reference.csv", "summary.json"] {
        std::fs::write(dir.join("v0.5").join(f), "x").unwrap();
    }
}

#[test]
fn serves_the_page_and_refuses_escapes() {
    let root = page("ok", true);
    let replay = root.join("runs");
    run_folder(&replay);
    let (mut child, port) =
        serve(&["--port", "0", "--root", root.to_str().unwrap(), "--replay", replay.to_str().unwrap()]);
    let (status, text) = get(port, "/");
    assert_eq!(status, "HTTP/1.1 200 OK");
    assert!(
        text.contains("Content-Type: text/html; charset=utf-8") && text.ends_with("<title>t</title>"),
        "{text}"
    );
    let (_, text) = get(port, "/pkg/meterstick_web.wasm");
    assert!(text.contains("Content-Type: application/wasm\r\nContent-Length: 8\r\n"), "{text}");
    assert!(get(port, "/app.js").1.contains("Content-Type: text/javascript; charset=utf-8"));
    assert!(get(port, "/../Cargo.toml").0.starts_with("HTTP/1.1 400"));
    assert!(get(port, "/pkg/%2e%2e/%2e%2e/etc/passwd").0.starts_with("HTTP/1.1 400"));
    assert!(get(port, "/nothing.js").0.starts_with("HTTP/1.1 404"));
    let (_, list) = get(port, "/replay/runs.json");
    assert!(list.ends_with(r#""runs":[{"name":"v0.5","path":"v0.5/"}]}"#), "{list}");
    assert!(get(port, "/replay/v0.5/core.csv").1.contains("Content-Type: text/csv; charset=utf-8"));
    child.kill().unwrap();
    child.wait().unwrap();
}

/// A file larger than the server's 64 KiB chunk arrives intact, byte for byte, with its length;
/// `HEAD` gives the length and no body. The server sends files a chunk at a time (before, it read
/// each whole into memory: six parallel requests for a 790 MB reference.csv ran out of memory).
#[test]
fn serves_a_file_of_several_chunks_intact() {
    let root = page("big", true);
    let bytes: Vec<u8> = (0..1_000_003u32).map(|i| (i.wrapping_mul(2_654_435_761) >> 24) as u8).collect();
    std::fs::write(root.join("big.csv"), &bytes).unwrap();
    let (mut child, port) = serve(&["--port", "0", "--root", root.to_str().unwrap()]);
    let fetches: Vec<_> =
        (0..4).map(|_| std::thread::spawn(move || request(port, "GET", "/big.csv"))).collect();
    for f in fetches {
        let (head, body) = f.join().unwrap();
        assert!(head.starts_with("HTTP/1.1 200 OK\r\n"), "{head}");
        assert!(
            head.contains("Content-Type: text/csv; charset=utf-8\r\nContent-Length: 1000003\r\n"),
            "{head}"
        );
        assert!(body == bytes, "{} bytes arrived, not the file's 1000003 (or other bytes)", body.len());
    }
    let (head, body) = request(port, "HEAD", "/big.csv");
    assert!(head.contains("Content-Length: 1000003\r\n") && body.is_empty(), "{head}");
    child.kill().unwrap();
    child.wait().unwrap();
    std::fs::remove_dir_all(&root).unwrap();
}

#[test]
fn refuses_to_start_without_the_module_or_a_run() {
    let root = page("nowasm", false);
    let out = Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args(["serve", "--port", "0", "--root", root.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(
        err.contains(
            "pkg/meterstick_web.wasm: missing; build the core for the browser first: bash scripts/web.sh"
        ),
        "{err}"
    );
    let root = page("norun", true);
    let out = Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args(["serve", "--port", "0", "--root", root.to_str().unwrap(), "--replay", root.to_str().unwrap()])
        .output()
        .unwrap();
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(err.contains(": no run of host-sim run in it (a folder with core.csv"), "{err}");
}
