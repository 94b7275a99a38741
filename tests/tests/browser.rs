//! The page in a real browser: headless Chromium driven over WebDriver (chromedriver, a few
//! requests over `std::net`: no async runtime), the page served by `host-sim serve`'s server
//! in-process. Ignored in a plain `cargo test` (it needs Chromium, chromedriver and the built
//! module `web/page/pkg/meterstick_web.wasm`); `scripts/test.sh` builds the module and runs it
//! with `--ignored`.
//!
//! It checks the URL contract against `host-sim scene` (the same outcome and the same trajectory
//! checksum, bit for bit, for the slow and a fast meter stick, an f64 8x8 run, the incline, the
//! ladder, three fingers, the cylinder rolling and sliding and Painleve's rod jamming and sliding;
//! on a difference it prints the first step that differs; for the scenes of one and three contacts
//! also the module they ran in, their contacts and the measured quantities shown, against
//! `host-sim`'s `summary.json` values; the tablecloth, block-on-block, a falling stack and a disc on
//! a pulled board rolling and sliding, scenes of several bodies, to the outcome, end state and
//! measured quantities of host-sim's core run),
//! that the scene selector loads a scene's module and runs
//! it, that the controls change the run
//! (typing, Enter, the keyboard shortcut) and that a bad value shows `host-sim`'s sentence, that a
//! click on the outcome map loads a run with the map's outcome, and the replay of a `host-sim run`
//! folder; it prints the page's steps per second and the map's time, and saves screenshots in
//! `out/browser/`.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::io::{Read, Write};
use std::net::{TcpListener, TcpStream};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use meterstick_host_sim::bodies;
use meterstick_host_sim::commands::{run as run_command, scene};
use meterstick_host_sim::lcp_io::Precision;
use meterstick_host_sim::scenes::{Catalogued as _, FLAGS, INTRODUCTIONS, LcpLayout, SceneArgs, SceneKind};
use meterstick_host_sim::serve::{Replay, ServeArgs, Server};
use meterstick_host_sim::trajectory::{Record, run_k};
use meterstick_host_sim::with_contacts;
use serde_json::{Value, json};

mod browser_spatial;

const ELEMENT: &str = "element-6066-11e4-a52e-4f735466cecf";

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap().to_path_buf()
}

fn free_port() -> u16 {
    TcpListener::bind("127.0.0.1:0").unwrap().local_addr().unwrap().port()
}

/// One HTTP/1.1 request; the status and body of the answer (read by its `Content-Length`, or
/// chunked: chromedriver may keep the connection open).
fn http(port: u16, method: &str, path: &str, body: Option<&Value>) -> std::io::Result<(u16, String)> {
    let mut s = TcpStream::connect(("127.0.0.1", port))?;
    s.set_read_timeout(Some(Duration::from_secs(120)))?;
    let payload = body.map(Value::to_string).unwrap_or_default();
    write!(
        s,
        "{method} {path} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nContent-Type: application/json\r\n\
         Content-Length: {}\r\nConnection: close\r\n\r\n{payload}",
        payload.len()
    )?;
    let mut raw = Vec::new();
    let mut buf = [0u8; 8192];
    let complete = |raw: &[u8]| -> Option<(u16, Vec<u8>)> {
        let end = raw.windows(4).position(|w| w == b"\r\n\r\n")?;
        let head = String::from_utf8_lossy(&raw[..end]).to_ascii_lowercase();
        let status = head.split(' ').nth(1).and_then(|c| c.parse().ok()).unwrap_or(0);
        let body = &raw[end + 4..];
        if let Some(len) = head.lines().find_map(|l| l.strip_prefix("content-length:")) {
            let len: usize = len.trim().parse().ok()?;
            return (body.len() >= len).then(|| (status, body[..len].to_vec()));
        }
        if head.contains("transfer-encoding: chunked") {
            let mut out = Vec::new();
            let mut rest = body;
            loop {
                let line_end = rest.windows(2).position(|w| w == b"\r\n")?;
                let size =
                    usize::from_str_radix(std::str::from_utf8(&rest[..line_end]).ok()?.trim(), 16).ok()?;
                if size == 0 {
                    return Some((status, out));
                }
                let chunk = rest.get(line_end + 2..line_end + 2 + size)?;
                out.extend_from_slice(chunk);
                rest = rest.get(line_end + 4 + size..)?;
            }
        }
        None
    };
    loop {
        if let Some((status, body)) = complete(&raw) {
            return Ok((status, String::from_utf8_lossy(&body).into_owned()));
        }
        let n = s.read(&mut buf)?;
        if n == 0 {
            let text = String::from_utf8_lossy(&raw).into_owned();
            let (head, body) = text.split_once("\r\n\r\n").unwrap_or((&text, ""));
            let status = head.split(' ').nth(1).and_then(|c| c.parse().ok()).unwrap_or(0);
            return Ok((status, body.to_owned()));
        }
        raw.extend_from_slice(&buf[..n]);
    }
}

/// A WebDriver session in headless Chromium.
struct Browser {
    driver: Child,
    port: u16,
    session: String,
    _profile: TempDir,
}

struct TempDir(PathBuf);

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

impl Browser {
    fn start() -> Self {
        let port = free_port();
        let driver = Command::new("chromedriver")
            .arg(format!("--port={port}"))
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("chromedriver (Debian package chromium-driver; scripts/setup.sh installs it)");
        let start = Instant::now();
        while !matches!(http(port, "GET", "/status", None), Ok((200, b)) if b.contains("\"ready\":true")) {
            assert!(start.elapsed() < Duration::from_secs(20), "chromedriver did not start");
            std::thread::sleep(Duration::from_millis(100));
        }
        let profile =
            TempDir(std::env::temp_dir().join(format!("meterstick-chromium-{}", std::process::id())));
        let caps = json!({"capabilities": {"alwaysMatch": {"browserName": "chrome", "goog:chromeOptions": {
            "binary": "/usr/bin/chromium",
            "args": ["--headless=new", "--no-sandbox", "--disable-gpu", "--enable-unsafe-swiftshader", "--disable-dev-shm-usage",
                     "--disable-quic", "--no-first-run", "--disable-background-networking",
                     "--disable-component-update", "--disable-sync", "--window-size=1600,1100",
                     format!("--user-data-dir={}", profile.0.display())]
        }}}});
        let (status, body) = http(port, "POST", "/session", Some(&caps)).unwrap();
        let v: Value = serde_json::from_str(&body).unwrap();
        assert_eq!(status, 200, "new session: {body}");
        let session = v["value"]["sessionId"].as_str().unwrap().to_owned();
        Self { driver, port, session, _profile: profile }
    }

    fn cmd(&self, method: &str, path: &str, body: Option<&Value>) -> Value {
        let url = format!("/session/{}{path}", self.session);
        let (status, text) = http(self.port, method, &url, body).unwrap();
        let v: Value = serde_json::from_str(&text).unwrap_or(Value::Null);
        assert_eq!(status, 200, "{method} {path}: {text}");
        v["value"].clone()
    }

    fn goto(&self, url: &str) {
        self.cmd("POST", "/url", Some(&json!({ "url": url })));
    }

    fn js(&self, script: &str) -> Value {
        self.cmd("POST", "/execute/sync", Some(&json!({ "script": script, "args": [] })))
    }

    fn text(&self, id: &str) -> String {
        self.js(&format!("return document.getElementById('{id}').textContent"))
            .as_str()
            .unwrap_or("")
            .to_owned()
    }

    fn find(&self, css: &str) -> String {
        let v = self.cmd("POST", "/element", Some(&json!({ "using": "css selector", "value": css })));
        v[ELEMENT].as_str().unwrap().to_owned()
    }

    fn click(&self, css: &str) {
        let e = self.find(css);
        self.cmd("POST", &format!("/element/{e}/click"), Some(&json!({})));
    }

    /// Clears a text field and types `text` into it (`\u{E007}` is Enter).
    fn type_into(&self, css: &str, text: &str) {
        let e = self.find(css);
        self.cmd("POST", &format!("/element/{e}/clear"), Some(&json!({})));
        self.cmd("POST", &format!("/element/{e}/value"), Some(&json!({ "text": text })));
    }

    /// Presses one key on whatever has the focus.
    fn key(&self, key: &str) {
        self.cmd(
            "POST",
            "/actions",
            Some(&json!({"actions": [{"type": "key", "id": "keyboard", "actions": [
                {"type": "keyDown", "value": key}, {"type": "keyUp", "value": key}]}]})),
        );
    }

    /// Clicks at `(x, y)` CSS pixels from the top left corner of the element.
    fn click_at(&self, css: &str, x: f64, y: f64) {
        let e = self.find(css);
        let rect = self.js(&format!(
            "const r = document.querySelector('{css}').getBoundingClientRect(); return [r.width, r.height]"
        ));
        let (w, h) = (rect[0].as_f64().unwrap(), rect[1].as_f64().unwrap());
        self.cmd(
            "POST",
            "/actions",
            Some(&json!({"actions": [{"type": "pointer", "id": "mouse", "parameters": {"pointerType": "mouse"}, "actions": [
                {"type": "pointerMove", "origin": {ELEMENT: e}, "x": (x - w / 2.0).round() as i64, "y": (y - h / 2.0).round() as i64},
                {"type": "pointerDown", "button": 0}, {"type": "pointerUp", "button": 0}]}]})),
        );
    }

    /// Waits until the script returns a truthy value; returns it.
    fn wait(&self, what: &str, script: &str, timeout: Duration) -> Value {
        let start = Instant::now();
        loop {
            let v = self.js(script);
            if v.as_bool() != Some(false) && !v.is_null() && v.as_str() != Some("") {
                return v;
            }
            if start.elapsed() > timeout {
                let state = self.js("return document.body.dataset.state + ': ' + document.getElementById('error').textContent + ' / ' + document.getElementById('status').textContent");
                panic!("timed out after {timeout:?} waiting for {what} (page: {state})");
            }
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    fn screenshot(&self, name: &str, css: Option<&str>) -> PathBuf {
        let b64 = if let Some(css) = css {
            let e = self.find(css);
            self.js(&format!("document.querySelector('{css}').scrollIntoView({{block: 'start'}})"));
            self.cmd("GET", &format!("/element/{e}/screenshot"), None)
        } else {
            self.js("window.scrollTo(0, 0)");
            self.cmd("GET", "/screenshot", None)
        };
        let dir = repo().join("out/browser");
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(format!("{name}.png"));
        std::fs::write(&path, base64(b64.as_str().unwrap())).unwrap();
        path
    }
}

impl Drop for Browser {
    fn drop(&mut self) {
        let _ = http(self.port, "DELETE", &format!("/session/{}", self.session), None);
        let _ = self.driver.kill();
        let _ = self.driver.wait();
    }
}

fn base64(s: &str) -> Vec<u8> {
    let value = |c: u8| match c {
        b'A'..=b'Z' => Some(c - b'A'),
        b'a'..=b'z' => Some(c - b'a' + 26),
        b'0'..=b'9' => Some(c - b'0' + 52),
        b'+' => Some(62),
        b'/' => Some(63),
        _ => None,
    };
    let digits: Vec<u8> = s.bytes().filter_map(value).collect();
    digits
        .chunks(4)
        .flat_map(|c| {
            let n = c.iter().enumerate().fold(0u32, |acc, (i, &d)| acc | (u32::from(d) << (18 - 6 * i)));
            let bytes = [(n >> 16) as u8, (n >> 8) as u8, n as u8];
            bytes.into_iter().take(c.len() - 1)
        })
        .collect()
}

/// The `host-sim scene` options for a page query (scene, flags, precision, LCP size).
fn scene_args(query: &str) -> SceneArgs {
    let mut args = SceneArgs::default();
    for pair in query.split('&') {
        let (key, value) = pair.split_once('=').unwrap();
        match key {
            "scene" => args.scene = Some(*SceneKind::ALL.iter().find(|k| k.name() == value).unwrap()),
            "precision" => args.precision = if value == "f64" { Precision::F64 } else { Precision::F32 },
            // The page's key names the two-contact size of the layout (6 reduced, 8 full).
            "lcp-size" => args.layout = if value == "8" { LcpLayout::Full } else { LcpLayout::Reduced },
            "autorun" | "rate" | "after" => {}
            // Run B's flags (the comparison): not run A's.
            b if b.starts_with("b.") => {}
            flag => {
                let f = FLAGS.iter().find(|f| f.long == flag).unwrap_or_else(|| panic!("no flag {flag}"));
                args.given.push((f, vec![value.parse().unwrap()]));
            }
        }
    }
    args
}

/// What `host-sim scene` prints for the query: (outcome, checksum).
fn host_scene(query: &str) -> (String, String) {
    let text = scene::run(&scene::SceneCmdArgs { scene: scene_args(query) }).unwrap();
    let outcome = text.split("outcome ").nth(1).and_then(|r| r.split(" at t = ").next()).unwrap().to_owned();
    let checksum = text.lines().find_map(|l| l.strip_prefix("checksum ")).unwrap().to_owned();
    (outcome, checksum)
}

/// The first step at which the page's trajectory differs from the host's (for the report).
#[allow(clippy::type_complexity)] // a closure for `?` in the macro's refusal
fn first_difference(b: &Browser, query: &str) -> String {
    let args = scene_args(query);
    let spec = args.specs(None).unwrap()[0].1;
    let rows = || -> Result<Vec<(f64, [f64; 6])>, Box<dyn std::error::Error + Send + Sync>> {
        Ok(with_contacts!(spec.kind(), K => {
            let t = run_k::<K>(&spec, args.implementation(), Record::All)?;
            t.rows.iter().map(|r| (r.t, [r.q[0], r.q[1], r.q[2], r.v[0], r.v[1], r.v[2]])).collect()
        }))
    };
    // A scene not recorded step by step against its supports (several bodies, three dimensions):
    // no rows of one body to compare.
    let Ok(host) = rows() else {
        return format!("{} has no trajectory of one body to compare step by step", spec.kind());
    };
    let page = b.js("return window.meterstick.trace()");
    let f32_run = args.precision == Precision::F32;
    let same = |a: f64, b: f64| {
        if f32_run { (a as f32).to_bits() == (b as f32).to_bits() } else { a.to_bits() == b.to_bits() }
    };
    let names = ["x", "y", "theta", "vx", "vy", "omega"];
    let steps = page["x"].as_array().map_or(0, Vec::len);
    for (k, (t, host_values)) in host.iter().enumerate().take(steps) {
        for (name, hv) in names.iter().zip(*host_values) {
            let pv = page[name][k].as_f64().unwrap_or(f64::NAN);
            if !same(pv, hv) {
                return format!("first difference at step {k} (t = {t}): {name} page {pv:e}, host {hv:e}");
            }
        }
    }
    format!("no state differs over {steps} page steps and {} host steps", host.len())
}

/// Loads the page with `query`, waits for the outcome, and checks it and the checksum against
/// `host-sim scene`'s. Returns the checksum.
pub(crate) fn check_contract(b: &Browser, base: &str, name: &str, query: &str) -> String {
    let started = Instant::now();
    b.goto(&format!("{base}?{query}"));
    let outcome = b.wait(
        "the outcome",
        "return document.getElementById('outcome').textContent",
        Duration::from_secs(120),
    );
    let outcome = outcome.as_str().unwrap().to_owned();
    let checksum = b.text("checksum");
    let (host_outcome, host_checksum) = host_scene(query);
    let shot = b.screenshot(name, None);
    println!(
        "{name}: ?{query}\n    page {outcome} {checksum}, host-sim scene {host_outcome} {host_checksum} ({:.1} s; {})",
        started.elapsed().as_secs_f64(),
        shot.display()
    );
    assert!(
        (outcome.as_str(), checksum.as_str()) == (host_outcome.as_str(), host_checksum.as_str()),
        "{name}: the page's f32/f64 build differs from host-sim scene: page {outcome} {checksum}, host {host_outcome} {host_checksum}; {}",
        first_difference(b, query)
    );
    checksum
}

#[test]
#[ignore = "needs Chromium, chromedriver and web/page/pkg/meterstick_web.wasm: run scripts/test.sh"]
fn the_page_in_chromium() {
    let root = repo().join("web/page");
    assert!(
        root.join("pkg/meterstick_web.wasm").is_file(),
        "web/page/pkg/meterstick_web.wasm is missing: bash scripts/web.sh --build (scripts/test.sh builds it)"
    );
    // A run of host-sim run to replay: the meter stick at 1 m/s.
    let replay = std::env::temp_dir().join(format!("meterstick-browser-replay-{}", std::process::id()));
    let mut run_args = SceneArgs::default();
    run_args.given.push((FLAGS.iter().find(|f| f.long == "speed").unwrap(), vec![1.0]));
    run_command::run(&run_command::RunArgs { scene: run_args, out: replay.clone() }).unwrap();
    let server = Server::bind(&ServeArgs { port: 0, root, replay: Some(replay.clone()) }).unwrap();
    let base = format!("http://{}/", server.local_addr().unwrap());
    std::thread::spawn(move || server.run());
    let b = Browser::start();

    // The URL contract, against host-sim scene: slow and fast meter stick (the fast one played in
    // real time, as the contract's example asks), f64 8x8, incline, ladder.
    let slow = check_contract(
        &b,
        &base,
        "meter-stick-slow",
        "scene=meter-stick&speed=0.1&mu-s=0.6&mu-k=0.4&x1=-0.35&autorun=1&rate=max",
    );
    check_contract(
        &b,
        &base,
        "meter-stick-fast",
        "scene=meter-stick&speed=1&mu-s=0.6&mu-k=0.4&x1=-0.35&autorun=1",
    );
    check_contract(
        &b,
        &base,
        "meter-stick-f64-8x8",
        "scene=meter-stick&speed=0.25&x1=-0.35&precision=f64&lcp-size=8&autorun=1&rate=max",
    );
    check_contract(&b, &base, "incline", "scene=incline&angle=30&mu-s=0.5&mu-k=0.3&autorun=1&rate=max");
    check_contract(&b, &base, "ladder", "scene=ladder&angle=60&mu-floor=0.2&mu-wall=0.1&autorun=1&rate=max");
    // The scenes of one and three contacts, in the modules of their contacts (the cylinder and
    // Painleve's jam played in real time: the animation, not only the result).
    check_scene(&b, &base, "cylinder-rolling", "scene=cylinder&angle=30&autorun=1", "Rolled");
    check_scene(
        &b,
        &base,
        "cylinder-sliding",
        "scene=cylinder&angle=70&precision=f64&lcp-size=8&autorun=1&rate=max",
        "Slid",
    );
    check_scene(&b, &base, "painleve-jammed", "scene=painleve&angle=30&mu-k=3&autorun=1", "Jammed");
    check_scene(
        &b,
        &base,
        "painleve-sliding",
        "scene=painleve&mu-s=1&mu-k=1&duration=0.1&lcp-size=8&autorun=1&rate=max",
        "Slid",
    );
    check_scene(&b, &base, "three-fingers", "scene=three-fingers&speed=0.2&autorun=1&rate=max", "Held");
    // The scenes of several bodies, in their module: the tablecloth pulled out from under the
    // block, a block riding on a block, a stack past its balance falling off the table's edge.
    check_bodies(&b, &base, "tablecloth", "scene=tablecloth&autorun=1&rate=max");
    check_bodies(&b, &base, "block-on-block", "scene=block-on-block&precision=f64&autorun=1&rate=max");
    check_bodies(&b, &base, "stack-falling", "scene=stack&overhang=1.5&autorun=1&rate=max");
    // A cylinder on a pulled board rolls back on it (Rolled, a_c = A / 3), and pulled beyond
    // A = 3 mu_s g slides (f64).
    check_bodies(&b, &base, "disc-on-board", "scene=disc-on-board&autorun=1&rate=max");
    check_bodies(
        &b,
        &base,
        "disc-on-board-sliding",
        "scene=disc-on-board&force=40&duration=0.2&precision=f64&autorun=1&rate=max",
    );
    // The scenes in three dimensions, in their module, drawn in perspective: each at its
    // defaults, and the puck on a slope as the URL contract's example.
    for scene in ["puck", "billiard", "curling", "meter-stick-3d", "stack-3d"] {
        browser_spatial::check_spatial(&b, &base, scene, &format!("scene={scene}&autorun=1&rate=max"));
    }
    browser_spatial::check_spatial(
        &b,
        &base,
        "curling-f64",
        "scene=curling&precision=f64&autorun=1&rate=max",
    );
    browser_spatial::check_spatial(
        &b,
        &base,
        "puck-contract",
        "scene=puck&angle=20&mu-k=0.3&speed=0.9&heading=15&autorun=1",
    );
    check_scene_selector(&b, &base);
    check_intros(&b, &base);
    check_pulled_block_in_view(&b, &base);
    check_stack_goes_on_falling(&b, &base);
    check_comparison(&b, &base);
    check_cautions(&b, &base);

    check_controls(&b, &base, &slow);
    check_map(&b, &base);
    check_replay(&b, &base, &replay);
    // The benchmark (a number to report, not a timed test).
    b.goto(&format!("{base}?bench=1"));
    b.wait(
        "the benchmark",
        "return document.getElementById('bench').dataset.stepsPerSecond",
        Duration::from_secs(60),
    );
    println!("page benchmark: {}", b.text("bench"));
    b.goto(&format!("{base}?scene=meter-stick&speed=0.1&x1=-0.35&autorun=1&rate=2"));
    std::thread::sleep(Duration::from_millis(2500));
    let shot = b.screenshot("meter-stick-playing", None);
    println!("mid-run screenshot: {}", shot.display());
    let _ = std::fs::remove_dir_all(&replay);
}

/// A scene of the catalogue on the page: the contract ([`check_contract`]), and the outcome
/// `expected` (so that the run shows what the scene is about), the module of its contacts, its
/// contacts and its measured quantities as `host-sim` measures them (`summary.json`'s keys, bit for
/// bit; the text shown is printed).
fn check_scene(b: &Browser, base: &str, name: &str, query: &str, expected: &str) {
    check_contract(b, base, name, query);
    assert_eq!(b.text("outcome"), expected, "{name}");
    let args = scene_args(query);
    let kind = args.scene.unwrap();
    let info = kind.info();
    let shown = b.js("return window.meterstick.contacts()");
    assert_eq!(shown["names"], json!(info.contact_names), "{name}: the contacts");
    assert_eq!(shown["row"].as_u64(), Some(7 + 6 * kind.contacts() as u64), "{name}: the row");
    let module = format!("pkg/meterstick_web_k{}.wasm", kind.contacts());
    let fetched = b.js("return performance.getEntriesByType('resource').map((e) => e.name).join(' ')");
    assert!(fetched.as_str().unwrap().contains(&module), "{name}: {module} not fetched: {fetched}");
    let spec = args.specs(None).unwrap()[0].1;
    let implementation = args.implementation();
    let measured = || -> Result<Value, Box<dyn std::error::Error + Send + Sync>> {
        Ok(
            with_contacts!(kind, K => serde_json::to_value(run_k::<K>(&spec, implementation, Record::Nothing)?.measured)?),
        )
    };
    let host = measured().unwrap();
    let values = b.js("return document.getElementById('measured').dataset.values");
    let page: Value = serde_json::from_str(values.as_str().unwrap()).unwrap();
    for key in info.measures {
        let theirs = key.split('.').fold(&host, |v, part| &v[part]);
        assert_eq!(
            page[key].as_f64().map(f64::to_bits),
            theirs.as_f64().map(f64::to_bits),
            "{name}: {key}: page {page}, host {host}"
        );
    }
    println!(
        "    {} contact(s) {:?}, from {module}; measured: {}",
        kind.contacts(),
        info.contact_names,
        b.text("measured")
    );
}

/// A scene of several bodies on the page (`query`): it runs in `meterstick_web_mb.wasm` to the
/// outcome, the end state (time and every body's x, y, theta, bit for bit) and the measured
/// quantities of host-sim's core run of the same flags.
fn check_bodies(b: &Browser, base: &str, name: &str, query: &str) {
    let started = Instant::now();
    b.goto(&format!("{base}?{query}"));
    let outcome = b.wait(
        "the outcome",
        "return document.getElementById('outcome').textContent",
        Duration::from_secs(90),
    );
    let args = scene_args(query);
    let spec = args.specs(None).unwrap()[0].1;
    let host = bodies::run_core(&spec, args.precision, false, None).unwrap();
    let shot = b.screenshot(name, None);
    println!(
        "{name}: ?{query}\n    page {}, host-sim's core {} ({:.1} s; {})",
        outcome.as_str().unwrap(),
        host.outcome.class.name(),
        started.elapsed().as_secs_f64(),
        shot.display()
    );
    assert_eq!(outcome.as_str(), Some(host.outcome.class.name()), "{name}: the outcome");
    let fetched = b.js("return performance.getEntriesByType('resource').map((e) => e.name).join(' ')");
    assert!(fetched.as_str().unwrap().contains("pkg/meterstick_web_mb.wasm"), "{name}: {fetched}");
    let last = b.js("return window.meterstick.lastRow()");
    let last: Vec<f64> = last.as_array().unwrap().iter().map(|v| v.as_f64().unwrap_or(f64::NAN)).collect();
    let mut want = vec![host.end_time];
    want.extend(host.last.q.iter().flatten());
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&last[..want.len()]), bits(&want), "{name}: the end state, page {last:?}, host {want:?}");
    let host_measured = serde_json::to_value(host.measured).unwrap();
    let values = b.js("return document.getElementById('measured').dataset.values");
    let page: Value = serde_json::from_str(values.as_str().unwrap()).unwrap();
    for key in args.scene.unwrap().info().measures {
        let theirs = key.split('.').fold(&host_measured, |v, part| &v[part]);
        assert_eq!(
            page[key].as_f64().map(f64::to_bits),
            theirs.as_f64().map(f64::to_bits),
            "{name}: {key}: page {page}, host {host_measured}"
        );
    }
    println!(
        "    {} bodies, from pkg/meterstick_web_mb.wasm; measured: {}",
        host.last.q.len(),
        b.text("measured")
    );
}

/// Each scene is headed and introduced as the catalogue's `INTRODUCTIONS` say (from
/// `pkg/intros.json`, which `build_web` writes from them).
fn check_intros(b: &Browser, base: &str) {
    // Every scene (`web::config::on_page`; those in three dimensions from their module).
    let on_page: Vec<_> = INTRODUCTIONS.iter().collect();
    for intro in &on_page {
        let name = intro.kind.name();
        b.goto(&format!("{base}?scene={name}"));
        b.wait(
            "the scene's heading",
            &format!(
                "return document.body.dataset.state === 'ready' && document.getElementById('heading').textContent === {}",
                json!(intro.heading)
            ),
            Duration::from_secs(30),
        );
        assert_eq!(b.text("intro"), intro.intro, "{name}: the introduction");
        assert_eq!(b.js("return document.title"), json!(format!("meterstick: {}", intro.heading)), "{name}");
    }
    println!("headings and introductions: the catalogue's, for {} scenes", on_page.len());
}

/// A body's box ([x, y] centre, [w, h] size, angle) inside a drawing's extent: every corner.
fn box_inside(x: f64, y: f64, theta: f64, size: &Value, extent: &Value) -> bool {
    let (w, h) = (size[0].as_f64().unwrap(), size[1].as_f64().unwrap());
    let e = |k: &str| extent[k].as_f64().unwrap();
    [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].iter().all(|(sx, sy)| {
        let (dx, dy) = (sx * w / 2.0, sy * h / 2.0);
        let cx = x + dx * theta.cos() - dy * theta.sin();
        let cy = y + dx * theta.sin() + dy * theta.cos();
        cx >= e("left") && cx <= e("right") && cy >= e("bottom") && cy <= e("top")
    })
}

/// Block-on-block pulled at 30 N, played in real time and on past its outcome: the view follows,
/// so the pulled block is inside the drawing in every frame, and at the end.
fn check_pulled_block_in_view(b: &Browser, base: &str) {
    let query = "scene=block-on-block&force=30&autorun=1";
    b.goto(&format!("{base}?{query}"));
    b.wait("the run and after", "return document.body.dataset.after === 'done'", Duration::from_secs(60));
    let (outcome, checksum) = host_scene(query);
    assert_eq!((b.text("outcome"), b.text("checksum")), (outcome.clone(), checksum.clone()), "{query}");
    let view = b.js("return window.meterstick.view()");
    assert!(view["worst"].as_f64().unwrap() >= 0.0, "a body left the drawing: {view}");
    // At the end, past the outcome: the pulled block's box within the drawing's extent now.
    let row = b.js("return window.meterstick.shownRow()");
    let at = |i: usize| row[i].as_f64().unwrap();
    assert!(
        box_inside(at(1), at(2), at(3), &view["sizes"][0], &view["extent"]),
        "the pulled block: {row} {view}"
    );
    let shot = b.screenshot("block-on-block-30N", None);
    println!(
        "block-on-block at 30 N: {outcome} {checksum}; the pulled block in the drawing in every frame (least room {:.0} px; {})",
        view["worst"].as_f64().unwrap(),
        shot.display()
    );
}

/// The stack past its balance (overhang 1.02) goes on after `Fell`: its top block ends more than a
/// block's height below its start, the outcome and the checksum staying the judged run's; its
/// CSV is offered and parses, the judged rows up to the outcome.
#[allow(clippy::float_cmp)] // exact: the CSV's numbers are the rows' own (JavaScript's shortest round trip)
fn check_stack_goes_on_falling(b: &Browser, base: &str) {
    let query = "scene=stack&overhang=1.02&autorun=1&rate=max";
    check_bodies(b, base, "stack-1.02", query);
    b.wait(
        "the fall after the outcome",
        "return document.body.dataset.after === 'done'",
        Duration::from_secs(60),
    );
    let (outcome, checksum) = host_scene(query);
    assert_eq!((b.text("outcome"), b.text("checksum")), (outcome.clone(), checksum.clone()), "as judged");
    let start = b.js("return window.meterstick.trace().y[0]").as_f64().unwrap();
    let end = b.js("return window.meterstick.shownRow()");
    let top = end[8].as_f64().unwrap();
    let height = b.js("return window.meterstick.view().sizes[2][1]").as_f64().unwrap();
    assert!(
        start - top > height,
        "the top block from y = {start} to {top}: not a block's height ({height}) lower"
    );
    let shot = b.screenshot("stack-1.02-after", None);
    println!(
        "stack at overhang 1.02: {outcome} {checksum}, then the top block from y = {start:.3} to {top:.3} m ({})",
        shot.display()
    );

    // The CSV: offered (the button), and parsed: a header, rows of numbers, t from 0, the judged
    // rows (after_outcome 0) ending at the outcome's row.
    assert_eq!(b.js("return document.getElementById('csv').disabled"), json!(false), "the CSV is offered");
    let csv = b.js("return window.meterstick.csv()");
    let mut lines = csv.as_str().unwrap().lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(
        header,
        ["t", "x1", "y1", "theta1", "x2", "y2", "theta2", "x3", "y3", "theta3", "after_outcome"]
    );
    let rows: Vec<Vec<f64>> = lines.map(|l| l.split(',').map(|v| v.parse().unwrap()).collect()).collect();
    assert!(rows.iter().all(|r| r.len() == header.len()));
    assert_eq!(rows[0][0], 0.0);
    let judged: Vec<&Vec<f64>> = rows.iter().filter(|r| r[10] == 0.0).collect();
    let last = b.js("return window.meterstick.lastRow()");
    let last: Vec<f64> = last.as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
    assert_eq!(judged.last().unwrap()[..10], last[..10], "the last judged row is the outcome's");
    assert!(rows.len() > judged.len(), "rows after the outcome");
    println!("    CSV: {} rows, {} up to the outcome", rows.len(), judged.len());
    // A scene of one body: core.csv's columns, the contacts' impulses among them.
    b.goto(&format!("{base}?scene=meter-stick&speed=1&x1=-0.35&autorun=1&rate=max"));
    b.wait("the outcome", "return document.getElementById('outcome').textContent", Duration::from_secs(60));
    let csv = b.js("return window.meterstick.csv()");
    let header = csv.as_str().unwrap().lines().next().unwrap().to_owned();
    assert_eq!(
        header,
        "t,x,y,theta,vx,vy,omega,support1_x,support1_y,support2_x,support2_y,mode1,mode2,pn1,pn2,pf1,pf2,along1,along2,after_outcome"
    );
}

/// Two runs side by side (`b.<flag>`): the tablecloth at 10 N and 20 N, each as host-sim runs it;
/// the harder pull moves the block less.
fn check_comparison(b: &Browser, base: &str) {
    b.goto(&format!("{base}?scene=tablecloth&force=10&b.force=20&autorun=1&rate=max"));
    b.wait("both outcomes", "return document.getElementById('outcome').textContent && document.getElementById('outcome-b').textContent", Duration::from_secs(60));
    let a = host_scene("scene=tablecloth&force=10");
    let bb = host_scene("scene=tablecloth&force=20");
    assert_eq!((b.text("outcome"), b.text("checksum")), a, "run A");
    assert_eq!((b.text("outcome-b"), b.text("checksum-b")), bb, "run B");
    let moved = |id: &str| {
        let v: Value = serde_json::from_str(
            b.js(&format!("return document.getElementById('{id}').dataset.values")).as_str().unwrap(),
        )
        .unwrap();
        v["block_displacement_m"].as_f64().unwrap()
    };
    let (ma, mb) = (moved("measured"), moved("measured-b"));
    assert!(mb < ma, "20 N moves the block less than 10 N: {mb} vs {ma}");
    assert!(b.js("return location.search").as_str().unwrap().contains("b.force=20"), "the URL keeps run B");
    let shot = b.screenshot("tablecloth-10-vs-20", None);
    println!(
        "comparison: tablecloth 10 N {} {} ({:.2} cm), 20 N {} {} ({:.2} cm) ({})",
        a.0,
        a.1,
        100.0 * ma,
        bb.0,
        bb.1,
        100.0 * mb,
        shot.display()
    );
    // The stack at overhang 0.98 holds, at 1.02 falls.
    b.goto(&format!("{base}?scene=stack&overhang=0.98&b.overhang=1.02&autorun=1&rate=max"));
    b.wait(
        "both outcomes",
        "return document.getElementById('outcome').textContent && document.getElementById('outcome-b').textContent",
        Duration::from_secs(60),
    );
    let a = host_scene("scene=stack&overhang=0.98");
    let bb = host_scene("scene=stack&overhang=1.02");
    assert_eq!((b.text("outcome"), b.text("checksum")), a, "run A");
    assert_eq!((b.text("outcome-b"), b.text("checksum-b")), bb, "run B");
    assert_eq!((a.0.as_str(), bb.0.as_str()), ("Held", "Fell"));
    let shot = b.screenshot("stack-0.98-vs-1.02", None);
    println!("comparison: stack 0.98 {} {}, 1.02 {} {} ({})", a.0, a.1, bb.0, bb.1, shot.display());
}

/// A run the precision may not follow is told so before it starts, in `host-sim scene`'s words
/// (its `warning:` lines, the flags without `--`): f32 with a 1e6 kg block on a 1 kg one, and with
/// friction beyond f32; the defaults are told nothing and show no caution.
fn check_cautions(b: &Browser, base: &str) {
    for query in [
        "scene=block-on-block&mass=1000000&mass2=1&duration=0.05&autorun=1&rate=max",
        "scene=meter-stick&mu-s=100000&mu-k=100000&duration=0.05&autorun=1&rate=max",
    ] {
        b.goto(&format!("{base}?{query}"));
        b.wait(
            "the cautions",
            "return document.getElementById('cautions').textContent !== ''",
            Duration::from_secs(30),
        );
        let text = scene::run(&scene::SceneCmdArgs { scene: scene_args(query) }).unwrap();
        let expected: Vec<String> = text
            .lines()
            .filter_map(|l| l.strip_prefix("warning: "))
            // The run's own round-off count (after the run) is host-sim's alone.
            .filter(|l| l.contains("friction beyond what") || l.contains(": mass ratio "))
            .map(|l| l.replace("--", ""))
            .collect();
        assert!(!expected.is_empty(), "host-sim warns {query}: {text}");
        let shown = b.js("return document.getElementById('cautions').textContent");
        let shown: Vec<String> = shown.as_str().unwrap().lines().map(String::from).collect();
        assert_eq!(shown, expected, "{query}");
        let visible = b.js("return getComputedStyle(document.getElementById('cautions')).display");
        assert_ne!(visible.as_str(), Some("none"), "{query}");
        println!("{query}: caution shown: {}", shown.join(" / "));
    }
    b.goto(&format!("{base}?scene=block-on-block&duration=0.05&autorun=1&rate=max"));
    b.wait(
        "the run",
        "return document.getElementById('outcome').textContent !== ''",
        Duration::from_secs(30),
    );
    assert_eq!(b.text("cautions"), "", "the defaults");
    let hidden = b.js("return getComputedStyle(document.getElementById('cautions')).display");
    assert_eq!(hidden.as_str(), Some("none"), "no caution row for the defaults");
}

/// The scene selector: choosing the cylinder loads its module and its flags, and the run it makes
/// is host-sim's.
fn check_scene_selector(b: &Browser, base: &str) {
    b.goto(&format!("{base}?scene=meter-stick&rate=max"));
    b.wait("the page", "return document.body.dataset.state === 'ready'", Duration::from_secs(30));
    let options = b.js("return [...document.getElementById('scene-select').options].map((o) => o.value)");
    // The first module's scenes in the catalogue's order, then those it does not name (the scenes
    // in three dimensions, from pkg/intros.json: by name).
    let mut names: Vec<&str> = SceneKind::ALL.iter().filter(|k| !k.is_spatial()).map(|k| k.name()).collect();
    let mut spatial: Vec<&str> = SceneKind::ALL.iter().filter(|k| k.is_spatial()).map(|k| k.name()).collect();
    spatial.sort_unstable();
    names.extend(spatial);
    assert_eq!(options, json!(names), "the selector lists the catalogue's scenes");
    let fetched = || b.js("return performance.getEntriesByType('resource').map((e) => e.name).join(' ')");
    assert!(
        !fetched().as_str().unwrap().contains("meterstick_web_sp.wasm"),
        "the module of the scenes in three dimensions is fetched when such a scene is chosen: {}",
        fetched()
    );
    assert!(
        !fetched().as_str().unwrap().contains("meterstick_web_k1.wasm"),
        "a two-contact scene needs only the first module: {}",
        fetched()
    );
    b.js("const s = document.getElementById('scene-select'); s.value = 'cylinder'; s.dispatchEvent(new Event('change'))");
    b.wait(
        "the cylinder's form",
        "return document.getElementById('p-radius') !== null && document.body.dataset.state === 'ready'",
        Duration::from_secs(30),
    );
    assert!(b.js("return location.search").as_str().unwrap().contains("scene=cylinder"), "the URL follows");
    assert_eq!(b.js("return document.getElementById('p-speed')"), Value::Null, "no finger flags");
    let (host_outcome, host_checksum) = type_and_run(b, "#p-angle", "65", "scene=cylinder&angle=65");
    let shot = b.screenshot("cylinder-selected", None);
    println!(
        "scene selector: cylinder, angle 65 typed, Space: {host_outcome} {host_checksum} ({})",
        shot.display()
    );
}

/// Types `value` and Enter into the field `selector` (a new run, paused), plays it with the Space
/// key and checks its outcome and checksum against `host-sim scene` with `query`'s flags; returns
/// them.
fn type_and_run(b: &Browser, selector: &str, value: &str, query: &str) -> (String, String) {
    b.type_into(selector, &format!("{value}\u{E007}"));
    b.wait("a new run", "return document.body.dataset.state === 'ready'", Duration::from_secs(10));
    b.js("document.activeElement.blur()");
    b.key(" ");
    let outcome = b.wait(
        "the outcome",
        "return document.getElementById('outcome').textContent",
        Duration::from_secs(60),
    );
    let (host_outcome, host_checksum) = host_scene(query);
    assert_eq!(
        (outcome.as_str().unwrap(), b.text("checksum").as_str()),
        (host_outcome.as_str(), host_checksum.as_str()),
        "{query}"
    );
    (host_outcome, host_checksum)
}

/// The controls change the run; a bad value shows host-sim's sentence.
fn check_controls(b: &Browser, base: &str, slow: &str) {
    // The controls: type a speed and press Enter (a new run, paused), play with the Space key.
    b.goto(&format!("{base}?scene=meter-stick&x1=-0.35&rate=max"));
    b.wait("the page", "return document.body.dataset.state === 'ready'", Duration::from_secs(30));
    assert_eq!(b.text("outcome"), "", "no outcome before the run");
    let (host_outcome, host_checksum) =
        type_and_run(b, "#p-speed", "1", "scene=meter-stick&x1=-0.35&speed=1");
    assert!(b.js("return location.search").as_str().unwrap().contains("speed=1"), "the URL follows the form");
    assert_ne!(host_checksum, slow, "the speed changed the run");
    println!("controls: speed 1 typed, Space pressed: {host_outcome} {host_checksum} (slow run: {slow})");

    // A bad value: the error in host-sim's words (without the `--`), no run.
    for (typed, query) in
        [("0.7", "scene=meter-stick&x1=-0.35&mu-k=0.7"), ("-0.6", "scene=meter-stick&x1=-0.6")]
    {
        let field = if query.ends_with("-0.6") { "#p-x1" } else { "#p-mu-k" };
        b.type_into(field, &format!("{typed}\u{E007}"));
        let shown = b.wait(
            "the error",
            "return document.getElementById('error').textContent",
            Duration::from_secs(10),
        );
        let host = scene::run(&scene::SceneCmdArgs { scene: scene_args(query) }).unwrap_err().to_string();
        assert_eq!(shown.as_str().unwrap(), host.replace("--", ""), "host-sim says: {host}");
        assert_eq!(
            b.js(&format!("return document.querySelector('{field}').getAttribute('aria-invalid')")),
            "true"
        );
        assert_eq!((b.text("outcome"), b.text("checksum")), (String::new(), String::new()));
        println!("bad value {field} {typed}: {}", shown.as_str().unwrap());
        b.type_into(field, if field == "#p-x1" { "-0.35\u{E007}" } else { "\u{E007}" });
    }
    b.type_into("#p-mu-s", "abc\u{E007}");
    assert_eq!(b.text("error"), "mu-s: \"abc\" is not a number");
    let shot = b.screenshot("error", Some(".params-panel"));
    println!("bad text: {} ({})", b.text("error"), shot.display());
}

/// The outcome map, and a click on one of its cells.
fn check_map(b: &Browser, base: &str) {
    // The outcome map: computed in workers; a click on a cell loads that run, with the map's outcome.
    b.goto(&format!("{base}?scene=meter-stick&rate=max"));
    b.wait("the page", "return document.body.dataset.state === 'ready'", Duration::from_secs(30));
    b.click("#map-run");
    let map_time =
        b.wait("the map", "return document.getElementById('map-time').textContent", Duration::from_secs(180));
    let map_status = b.text("map-status");
    let shot = b.screenshot("map", Some(".map-panel"));
    println!("map: {map_status} ({})", shot.display());
    // The cell at 0.25 m/s, mu_k/mu_s = 0.65 (i = 15, j = 9): where the canvas draws it.
    let at = b.js("return window.meterstick.mapCellCenter(15, 9)");
    b.click_at("#map", at[0].as_f64().unwrap(), at[1].as_f64().unwrap());
    b.wait(
        "the cell's run",
        "return document.getElementById('p-speed').value === '0.25'",
        Duration::from_secs(10),
    );
    let mu_k = b.js("return document.getElementById('p-mu-k').value");
    let outcome = b.wait(
        "the outcome",
        "return document.getElementById('outcome').textContent",
        Duration::from_secs(60),
    );
    let cell = b.js("return window.meterstick.mapOutcome(15, 9)").as_i64().unwrap();
    let names = ["Balanced", "Fell"];
    assert_eq!(
        outcome.as_str(),
        names.get(cell as usize).copied(),
        "the map's cell and the run it loads agree"
    );
    let (host_outcome, _) =
        host_scene(&format!("scene=meter-stick&speed=0.25&mu-k={}", mu_k.as_str().unwrap()));
    assert_eq!(outcome.as_str().unwrap(), host_outcome);
    println!(
        "map click: speed 0.25, mu-k {} -> {host_outcome}, as the map's cell; the map took {} s",
        mu_k.as_str().unwrap(),
        map_time.as_str().unwrap()
    );
}

/// The replay of a host-sim run folder.
fn check_replay(b: &Browser, base: &str, replay: &Path) {
    // The replay of host-sim run's folder.
    let name = Replay::find(replay).unwrap().runs[0].name.clone();
    b.goto(&format!("{base}?replay={name}&rate=max"));
    b.wait(
        "the replay",
        "return document.getElementById('run-info').textContent.startsWith('replay')",
        Duration::from_secs(30),
    );
    b.click("#play");
    let outcome = b.wait(
        "the end of the replay",
        "return document.getElementById('outcome').textContent",
        Duration::from_secs(60),
    );
    let summary: Value =
        serde_json::from_str(&std::fs::read_to_string(replay.join(&name).join("summary.json")).unwrap())
            .unwrap();
    assert_eq!(outcome, summary["core"]["outcome"], "the replay ends as host-sim run's core run");
    let shot = b.screenshot("replay", None);
    println!("replay of host-sim run {name}: {} ({})", outcome.as_str().unwrap(), shot.display());
}
