//! The server of `host-sim serve` ([`crate::commands::serve`]): the browser page (`web/page/`,
//! with the core compiled to WebAssembly in `web/page/pkg/`) over HTTP on `127.0.0.1`, and
//! optionally runs written by `host-sim run` to replay in it (`--replay DIR`, under `/replay/`,
//! listed in `/replay/runs.json`).
//!
//! A small HTTP/1.1 file server on `std::net` (one thread per connection, `Connection: close`):
//! `GET` and `HEAD` only; a path is percent-decoded and refused when it has a `..` or `.` segment,
//! a backslash or a NUL, and the file it names must lie under the served folder after symbolic
//! links are resolved; a folder serves its `index.html`; content types for `.html`, `.css`, `.js`,
//! `.wasm`, `.json`, `.csv`, `.svg`, `.png`.

use std::fmt::Write as _;
use std::io::{BufWriter, Read, Write};
use std::net::{SocketAddr, TcpListener, TcpStream};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

use anyhow::{Context as _, bail};

/// The module the page loads, relative to the page's folder.
pub const WASM: &str = "pkg/meterstick_web.wasm";

/// Longest request head accepted (request line and headers).
const MAX_HEAD: usize = 16 * 1024;
/// Connections served at once; more are answered `503`.
const MAX_CONNECTIONS: usize = 32;
/// A file is sent in chunks of this size: a connection holds one chunk, not the file (32
/// connections sending a 790 MB `reference.csv` each would otherwise hold 25 GB).
const CHUNK: usize = 64 * 1024;

/// `host-sim serve` options.
#[derive(Debug, Clone, clap::Args)]
pub struct ServeArgs {
    /// Port on 127.0.0.1 (0: any free port; the address is printed).
    #[arg(long, default_value_t = 8000)]
    pub port: u16,
    /// The page's folder: index.html and pkg/meterstick_web.wasm (built by `bash scripts/web.sh`).
    #[arg(long, default_value = "web/page")]
    pub root: PathBuf,
    /// A run written by `host-sim run` (a folder with core.csv, reference.csv and summary.json), or
    /// a folder of such runs (e.g. out/run), to replay in the page.
    #[arg(long, value_name = "DIR")]
    pub replay: Option<PathBuf>,
}

/// One run to replay: its name and its folder relative to the replay folder (`""` or `"v0.1/"`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ReplayRun {
    /// The run's name (its folder's).
    pub name: String,
    /// Its folder under `/replay/`, with a trailing `/` (empty for the replay folder itself).
    pub path: String,
}

/// The folder of runs to replay.
#[derive(Debug, Clone)]
pub struct Replay {
    /// The folder, as given.
    pub shown: PathBuf,
    /// The folder, resolved.
    pub dir: PathBuf,
    /// Its runs, in `host-sim run`'s order.
    pub runs: Vec<ReplayRun>,
}

impl Replay {
    /// The runs in `dir`: `dir` itself when it is a run, else its sub-folders that are (in the
    /// order of `dir/summary.json`'s `runs`, else by name).
    ///
    /// # Errors
    /// `dir` is not a folder, or holds no run.
    pub fn find(dir: &Path) -> anyhow::Result<Self> {
        let is_run =
            |d: &Path| ["core.csv", "reference.csv", "summary.json"].iter().all(|f| d.join(f).is_file());
        let resolved =
            dir.canonicalize().with_context(|| format!("--replay {}: no such folder", dir.display()))?;
        if !resolved.is_dir() {
            bail!("--replay {}: not a folder", dir.display());
        }
        let mut runs = Vec::new();
        if is_run(&resolved) {
            let name =
                resolved.file_name().map_or_else(|| "run".into(), |n| n.to_string_lossy().into_owned());
            runs.push(ReplayRun { name, path: String::new() });
        } else {
            let mut names: Vec<String> = std::fs::read_dir(&resolved)
                .with_context(|| format!("reading {}", dir.display()))?
                .filter_map(Result::ok)
                .filter(|e| is_run(&e.path()))
                .filter_map(|e| e.file_name().to_str().map(str::to_owned))
                .collect();
            names.sort();
            // host-sim run's summary.json lists its runs in the order they were asked for.
            let order: Vec<String> =
                crate::input::read_text(&resolved.join("summary.json"), crate::input::SUMMARY_FILE_CAP)
                    .ok()
                    .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok())
                    .and_then(|v| {
                        v["runs"].as_array().map(|runs| {
                            runs.iter().filter_map(|r| r["name"].as_str().map(str::to_owned)).collect()
                        })
                    })
                    .unwrap_or_default();
            names.sort_by_key(|n| order.iter().position(|o| o == n).unwrap_or(usize::MAX));
            runs = names.into_iter().map(|name| ReplayRun { path: format!("{name}/"), name }).collect();
        }
        if runs.is_empty() {
            bail!(
                "--replay {}: no run of host-sim run in it (a folder with core.csv, reference.csv and \
                 summary.json, or a folder of such folders, e.g. out/run)",
                dir.display()
            );
        }
        Ok(Self { shown: dir.to_path_buf(), dir: resolved, runs })
    }

    /// `/replay/runs.json`: `{"dir": ..., "runs": [{"name": ..., "path": ...}]}`.
    #[must_use]
    pub fn runs_json(&self) -> String {
        let runs: Vec<serde_json::Value> =
            self.runs.iter().map(|r| serde_json::json!({ "name": r.name, "path": r.path })).collect();
        serde_json::json!({ "dir": self.shown.display().to_string(), "runs": runs }).to_string()
    }
}

/// What the server serves.
#[derive(Debug)]
struct Site {
    root: PathBuf,
    replay: Option<Replay>,
}

/// A bound server, ready to [`Server::run`].
#[derive(Debug)]
pub struct Server {
    listener: TcpListener,
    site: Arc<Site>,
    shown_root: PathBuf,
}

impl Server {
    /// Checks the page's folder (and the replay folder) and binds `127.0.0.1:port`.
    ///
    /// # Errors
    /// No page or no wasm module in `root`, a bad replay folder, or a port that cannot be bound.
    pub fn bind(args: &ServeArgs) -> anyhow::Result<Self> {
        let root = &args.root;
        if !root.join("index.html").is_file() {
            bail!(
                "--root {}: no index.html there (run host-sim from the repository's root, or give --root web/page)",
                root.display()
            );
        }
        if !root.join(WASM).is_file() {
            bail!(
                "{}: missing; build the core for the browser first: bash scripts/web.sh (builds it and serves the page)",
                root.join(WASM).display()
            );
        }
        let resolved = root.canonicalize().with_context(|| format!("--root {}", root.display()))?;
        let replay = args.replay.as_deref().map(Replay::find).transpose()?;
        let addr = SocketAddr::from(([127, 0, 0, 1], args.port));
        let listener = TcpListener::bind(addr).map_err(|e| {
            if e.kind() == std::io::ErrorKind::AddrInUse {
                anyhow::anyhow!(
                    "--port {}: 127.0.0.1:{} is in use (choose another port; 0 picks a free one)",
                    args.port,
                    args.port
                )
            } else {
                anyhow::anyhow!("--port {}: cannot listen on {addr}: {e}", args.port)
            }
        })?;
        Ok(Self { listener, site: Arc::new(Site { root: resolved, replay }), shown_root: root.clone() })
    }

    /// The address it listens on.
    ///
    /// # Errors
    /// The socket's.
    pub fn local_addr(&self) -> std::io::Result<SocketAddr> {
        self.listener.local_addr()
    }

    /// The line printed when it starts: where the page is, and what it replays.
    ///
    /// # Errors
    /// The socket's.
    pub fn banner(&self) -> std::io::Result<String> {
        let mut s = format!("serving {} at http://{}/", self.shown_root.display(), self.local_addr()?);
        if let Some(r) = &self.site.replay {
            let names: Vec<&str> = r.runs.iter().map(|r| r.name.as_str()).collect();
            let _ = write!(s, " (replay {}: {})", r.shown.display(), names.join(", "));
        }
        Ok(s)
    }

    /// Serves until the process ends, one thread per connection.
    pub fn run(self) {
        let active = Arc::new(AtomicUsize::new(0));
        for stream in self.listener.incoming() {
            let Ok(stream) = stream else { continue };
            if active.fetch_add(1, Ordering::SeqCst) >= MAX_CONNECTIONS {
                active.fetch_sub(1, Ordering::SeqCst);
                let _ = respond(&stream, Response::text(503, "too many connections"), false);
                continue;
            }
            let site = Arc::clone(&self.site);
            let active = Arc::clone(&active);
            std::thread::spawn(move || {
                let _ = serve_connection(&stream, &site);
                active.fetch_sub(1, Ordering::SeqCst);
            });
        }
    }
}

/// A response: status, content type, body.
#[derive(Debug)]
struct Response {
    status: u16,
    content_type: &'static str,
    body: Body,
    allow: bool,
}

/// A response's body: bytes, or a file of a known length, sent in chunks of [`CHUNK`] bytes.
#[derive(Debug)]
enum Body {
    Bytes(Vec<u8>),
    File(std::fs::File, u64),
}

impl Body {
    /// Its length in bytes (`Content-Length`).
    fn len(&self) -> u64 {
        match self {
            Self::Bytes(b) => b.len() as u64,
            Self::File(_, len) => *len,
        }
    }

    /// Writes it to `w`; a file is read and written one chunk at a time, exactly its length (a
    /// file that shrank while it was sent ends the connection short of `Content-Length`).
    fn write_to(&mut self, w: &mut impl Write) -> std::io::Result<()> {
        match self {
            Self::Bytes(b) => w.write_all(b),
            Self::File(file, len) => {
                let mut chunk = vec![0u8; CHUNK];
                let mut left = *len;
                while left > 0 {
                    let want = usize::try_from(left).map_or(CHUNK, |l| l.min(CHUNK));
                    let n = file.read(&mut chunk[..want])?;
                    if n == 0 {
                        return Err(std::io::ErrorKind::UnexpectedEof.into());
                    }
                    w.write_all(&chunk[..n])?;
                    left -= n as u64;
                }
                Ok(())
            }
        }
    }
}

impl Response {
    fn text(status: u16, message: &str) -> Self {
        Self {
            status,
            content_type: "text/plain; charset=utf-8",
            body: Body::Bytes(format!("{status} {}: {message}\n", reason(status)).into_bytes()),
            allow: status == 405,
        }
    }
}

const fn reason(status: u16) -> &'static str {
    match status {
        200 => "OK",
        400 => "Bad Request",
        404 => "Not Found",
        405 => "Method Not Allowed",
        431 => "Request Header Fields Too Large",
        503 => "Service Unavailable",
        _ => "Internal Server Error",
    }
}

/// The content type of a file, by its extension.
#[must_use]
pub fn content_type(path: &Path) -> &'static str {
    match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
        Some("html" | "htm") => "text/html; charset=utf-8",
        Some("css") => "text/css; charset=utf-8",
        Some("js" | "mjs") => "text/javascript; charset=utf-8",
        Some("wasm") => "application/wasm",
        Some("json") => "application/json",
        Some("csv") => "text/csv; charset=utf-8",
        Some("svg") => "image/svg+xml",
        Some("png") => "image/png",
        Some("txt" | "md") => "text/plain; charset=utf-8",
        _ => "application/octet-stream",
    }
}

/// Reads the request head (up to the blank line).
fn read_head(mut stream: &TcpStream) -> Result<String, u16> {
    let mut head = Vec::with_capacity(1024);
    let mut buf = [0u8; 2048];
    loop {
        let n = stream.read(&mut buf).map_err(|_| 400u16)?;
        if n == 0 {
            return Err(400);
        }
        head.extend_from_slice(&buf[..n]);
        if let Some(end) = head.windows(4).position(|w| w == b"\r\n\r\n") {
            head.truncate(end);
            return String::from_utf8(head).map_err(|_| 400);
        }
        if head.len() > MAX_HEAD {
            return Err(431);
        }
    }
}

fn serve_connection(stream: &TcpStream, site: &Site) -> std::io::Result<()> {
    stream.set_read_timeout(Some(Duration::from_secs(10)))?;
    stream.set_write_timeout(Some(Duration::from_secs(30)))?;
    let (response, head_only) = match read_head(stream) {
        Ok(head) => answer(&head, site),
        Err(status) => (Response::text(status, "unreadable request"), false),
    };
    if response.status >= 400
        && let Body::Bytes(body) = &response.body
    {
        eprintln!(
            "host-sim serve: {} {}",
            response.status,
            String::from_utf8_lossy(body).trim_end().trim_start_matches(char::is_numeric).trim()
        );
    }
    respond(stream, response, head_only)
}

fn respond(stream: &TcpStream, mut r: Response, head_only: bool) -> std::io::Result<()> {
    let mut w = BufWriter::new(stream);
    write!(
        w,
        "HTTP/1.1 {} {}\r\nContent-Type: {}\r\nContent-Length: {}\r\nCache-Control: no-cache\r\n\
         X-Content-Type-Options: nosniff\r\nConnection: close\r\n",
        r.status,
        reason(r.status),
        r.content_type,
        r.body.len()
    )?;
    if r.allow {
        w.write_all(b"Allow: GET, HEAD\r\n")?;
    }
    w.write_all(b"\r\n")?;
    if !head_only {
        r.body.write_to(&mut w)?;
    }
    w.flush()
}

/// The response to a request head, and whether to send the head only (`HEAD`).
fn answer(head: &str, site: &Site) -> (Response, bool) {
    let line = head.lines().next().unwrap_or("");
    let mut parts = line.split(' ');
    let (Some(method), Some(target), Some(version), None) =
        (parts.next(), parts.next(), parts.next(), parts.next())
    else {
        return (Response::text(400, "the request line is not `METHOD /path HTTP/1.1`"), false);
    };
    if !version.starts_with("HTTP/1.") {
        return (Response::text(400, &format!("unsupported protocol {version:?}")), false);
    }
    let head_only = match method {
        "GET" => false,
        "HEAD" => true,
        _ => return (Response::text(405, &format!("{method} is not served (GET and HEAD are)")), false),
    };
    (route(target, site), head_only)
}

/// Maps a request target to a file (or the replay list).
fn route(target: &str, site: &Site) -> Response {
    let path = target.split(['?', '#']).next().unwrap_or("");
    let Some(path) = path.strip_prefix('/') else {
        return Response::text(400, &format!("{target:?} is not a path"));
    };
    let decoded = match percent_decode(path) {
        Ok(p) => p,
        Err(why) => return Response::text(400, &format!("{target:?}: {why}")),
    };
    if let Some(rest) = decoded.strip_prefix("replay/") {
        let Some(replay) = &site.replay else {
            return Response::text(404, "no runs to replay (host-sim serve --replay DIR)");
        };
        if rest == "runs.json" {
            return Response {
                status: 200,
                content_type: "application/json",
                body: Body::Bytes(replay.runs_json().into_bytes()),
                allow: false,
            };
        }
        return file(&replay.dir, rest);
    }
    file(&site.root, &decoded)
}

/// Decodes `%XX` escapes; the result must be UTF-8.
///
/// # Errors
/// A malformed escape, or bytes that are not UTF-8.
pub fn percent_decode(s: &str) -> Result<String, &'static str> {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = bytes.get(i + 1..i + 3).and_then(|h| std::str::from_utf8(h).ok());
            let value = hex.and_then(|h| u8::from_str_radix(h, 16).ok()).ok_or("a malformed %-escape")?;
            out.push(value);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).map_err(|_| "not UTF-8 after %-decoding")
}

/// The file at `rel` (a decoded path, `/`-separated) under `base`, or why not.
///
/// # Errors
/// (As a status.) A `..` or `.` segment, a backslash or NUL (400); nothing there, or a file
/// outside `base` once links are resolved (404).
pub fn resolve(base: &Path, rel: &str) -> Result<PathBuf, (u16, String)> {
    let mut path = base.to_path_buf();
    for segment in rel.split('/') {
        if segment.is_empty() {
            continue;
        }
        if segment == ".." || segment == "." || segment.contains(['\\', '\0']) {
            return Err((400, format!("/{rel}: a path may not contain `..`, `.`, backslashes or NUL")));
        }
        path.push(segment);
    }
    if path.is_dir() {
        path.push("index.html");
    }
    let not_found = || (404, format!("/{rel}: no such file"));
    let real = path.canonicalize().map_err(|_| not_found())?;
    if !real.starts_with(base) || !real.is_file() {
        return Err(not_found());
    }
    Ok(real)
}

/// The file at `rel` under `base` (opened, sent in chunks by [`respond`]), or why not.
fn file(base: &Path, rel: &str) -> Response {
    match resolve(base, rel) {
        Ok(path) => match crate::input::open(&path, crate::input::SERVED_FILE_CAP) {
            Ok((file, len)) => Response {
                status: 200,
                content_type: content_type(&path),
                body: Body::File(file, len),
                allow: false,
            },
            Err(e) => Response::text(500, &format!("/{rel}: {e:#}")),
        },
        Err((status, why)) => Response::text(status, &why),
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    fn site() -> (PathBuf, Site) {
        let dir = std::env::temp_dir().join(format!("meterstick-serve-unit-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("pkg")).unwrap();
        std::fs::write(dir.join("index.html"), "<!doctype html>").unwrap();
        std::fs::write(dir.join("pkg/meterstick_web.wasm"), b"\0asm").unwrap();
        let root = dir.canonicalize().unwrap();
        (dir, Site { root, replay: None })
    }

    fn body(mut r: Response) -> Vec<u8> {
        let mut out = Vec::new();
        r.body.write_to(&mut out).unwrap();
        out
    }

    #[test]
    fn content_types_by_extension() {
        assert_eq!(content_type(Path::new("a/b.wasm")), "application/wasm");
        assert_eq!(content_type(Path::new("app.js")), "text/javascript; charset=utf-8");
        assert_eq!(content_type(Path::new("index.HTML")), "text/html; charset=utf-8");
        assert_eq!(content_type(Path::new("core.csv")), "text/csv; charset=utf-8");
        assert_eq!(content_type(Path::new("summary.json")), "application/json");
        assert_eq!(content_type(Path::new("style.css")), "text/css; charset=utf-8");
        assert_eq!(content_type(Path::new("x")), "application/octet-stream");
    }

    #[test]
    fn percent_decoding() {
        assert_eq!(percent_decode("a%20b").unwrap(), "a b");
        assert_eq!(percent_decode("%2e%2E").unwrap(), "..");
        assert!(percent_decode("%zz").is_err());
        assert!(percent_decode("%2").is_err());
        assert!(percent_decode("%ff").is_err());
    }

    #[test]
    fn routes_files_and_refuses_escapes() {
        let (_dir, site) = site();
        let ok = route("/", &site);
        assert_eq!((ok.status, ok.content_type), (200, "text/html; charset=utf-8"));
        assert_eq!(ok.body.len(), 15);
        assert_eq!(body(ok), b"<!doctype html>");
        let wasm = route("/pkg/meterstick_web.wasm?v=1", &site);
        assert_eq!((wasm.status, wasm.content_type), (200, "application/wasm"));
        for bad in ["/../Cargo.toml", "/pkg/..%2f..%2fetc/passwd", "/%2e%2e/x", "/a\\b", "/./index.html"] {
            assert_eq!(route(bad, &site).status, 400, "{bad}");
        }
        assert_eq!(route("/missing.js", &site).status, 404);
        assert_eq!(route("/replay/runs.json", &site).status, 404, "no replay folder");
        assert_eq!(route("no-slash", &site).status, 400);
        let (r, head_only) = answer("POST / HTTP/1.1", &site);
        assert_eq!((r.status, r.allow, head_only), (405, true, false));
        assert!(answer("HEAD / HTTP/1.1", &site).1);
        assert_eq!(answer("GET / SPDY/3", &site).0.status, 400);
        assert_eq!(answer("GET /", &site).0.status, 400);
    }

    /// A file of several chunks (and a part) is sent whole, its length from the metadata; a file
    /// that shrinks while it is sent ends short of its length with an error (the connection closes
    /// and the client sees fewer bytes than `Content-Length`).
    #[test]
    fn a_file_is_sent_in_chunks_exactly() {
        let (dir, site) = site();
        let bytes: Vec<u8> = (0..3 * CHUNK + 17).map(|i| (i % 251) as u8).collect();
        std::fs::write(dir.join("big.bin"), &bytes).unwrap();
        let r = route("/big.bin", &site);
        assert_eq!((r.status, r.body.len()), (200, bytes.len() as u64));
        assert_eq!(body(r), bytes);
        let mut r = route("/big.bin", &site);
        std::fs::write(dir.join("big.bin"), &bytes[..CHUNK]).unwrap();
        let mut out = Vec::new();
        assert_eq!(r.body.write_to(&mut out).unwrap_err().kind(), std::io::ErrorKind::UnexpectedEof);
        assert_eq!(out.len(), CHUNK);
    }

    #[cfg(unix)]
    #[test]
    fn a_link_out_of_the_root_is_not_followed() {
        let (dir, site) = site();
        let outside = std::env::temp_dir().join(format!("meterstick-serve-outside-{}", std::process::id()));
        std::fs::write(&outside, "secret").unwrap();
        let link = dir.join("leak.txt");
        let _ = std::fs::remove_file(&link);
        std::os::unix::fs::symlink(&outside, &link).unwrap();
        assert_eq!(route("/leak.txt", &site).status, 404);
    }
}
