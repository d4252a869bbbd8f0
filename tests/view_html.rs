//! Issue 36, `flexbody view FILE -o body.html`: one self-contained page that animates the
//! modes.
//!
//! * Without a browser: the page loads nothing from outside (no URL, no `src=`, no `<link>`);
//!   its key figures are the file's (mass, every frequency, the interface names); its embedded
//!   data, decoded here (base64 float32), are the file's coordinates and mode shapes to float32
//!   rounding.
//! * In headless Chromium (skipped visibly without one; CI installs `chromium`): the page loads
//!   without a console message or script error, draws the body (its `data-status`, the mode
//!   shown, the number of pixels drawn), and mode 7 (`#mode=7&t=0.25`) draws different pixels
//!   than mode 1 — by the page's own canvas hash and by Chromium's screenshots.

use std::path::PathBuf;
use std::process::Command;

use crate::common::{exe, scratch, skipped_install};
use flexbody::export::vtu::significant;
use flexbody_reader as file;

fn run(args: &[&str]) {
    let o = exe().args(args).output().unwrap();
    assert!(
        o.status.success(),
        "flexbody {args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// Builds the conrod (CB, damping) and writes its page; (body, page path, folder).
fn conrod_page(name: &str) -> (file::ReducedBody, PathBuf, PathBuf) {
    let dir = scratch(&format!("view-{name}"));
    let body_path = dir.join("conrod.flexbody");
    let html = dir.join("conrod.html");
    crate::common::build_conrod(&body_path, &["--damping", "2%"]);
    run(&[
        "view",
        body_path.to_str().unwrap(),
        "-o",
        html.to_str().unwrap(),
    ]);
    (file::read(&body_path).unwrap(), html, dir)
}

fn f32s(text: &str) -> Vec<f32> {
    crate::common::base64_block(text)
        .0
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes(b.try_into().unwrap()))
        .collect()
}

#[test]
fn the_page_is_self_contained_and_holds_the_files_figures_and_shapes() {
    let (body, html_path, dir) = conrod_page("offline");
    let html = std::fs::read_to_string(&html_path).unwrap();
    println!("conrod page: {} bytes", html.len());
    let lower = html.to_ascii_lowercase();
    for outside in [
        "http://", "https://", "src=", "<link", "@import", "url(", "//cdn",
    ] {
        assert!(
            !lower.contains(outside),
            "the page refers outside: {outside}"
        );
    }
    // Key figures as the file has them.
    let mass = body.invariants.i1[0];
    assert!(html.contains(&format!("{} kg", significant(mass, 6))));
    for &f in &body.modes.frequency_hz {
        assert!(
            html.contains(&format!("<td>{}</td>", significant(f, 6))),
            "{f} Hz"
        );
    }
    for name in ["BIG_END", "SMALL_END"] {
        assert!(html.contains(name));
    }
    // The embedded data against the file.
    let start = html.find("id=\"flexbody-data\">").unwrap() + "id=\"flexbody-data\">".len();
    let end = start + html[start..].find("</script>").unwrap();
    let data: serde_json::Value = serde_json::from_str(&html[start..end]).unwrap();
    let xyz = f32s(data["xyz"].as_str().unwrap());
    // The page's nodes: those of the faces and the interface nodes, in stored order.
    let mut shown = vec![false; body.node_count()];
    for face in &body.faces {
        let nodes: &[u32] = match face {
            file::Face::Tri(v) => v,
            file::Face::Quad(v) => v,
        };
        for &p in nodes {
            shown[p as usize] = true;
        }
    }
    let stored: Vec<usize> = (0..body.node_count())
        .filter(|&p| shown[p] || body.nodes[p].interface)
        .collect();
    assert_eq!(xyz.len(), 3 * stored.len());
    for (i, &p) in stored.iter().enumerate() {
        for c in 0..3 {
            assert_eq!(xyz[3 * i + c], body.nodes[p].xyz[c] as f32);
        }
    }
    let modes = data["modes"].as_array().unwrap();
    assert_eq!(modes.len(), body.mode_count());
    let n = body.node_count();
    for (j, m) in modes.iter().enumerate() {
        assert_eq!(m["number"], j + 1);
        assert_eq!(m["hz"].as_f64().unwrap(), body.modes.frequency_hz[j]);
        let shape = f32s(m["shape"].as_str().unwrap());
        for (i, &p) in stored.iter().enumerate() {
            for c in 0..3 {
                assert_eq!(
                    shape[3 * i + c],
                    body.modes.shapes[(j * n + p) * 6 + c] as f32
                );
            }
        }
    }
    let names: Vec<&str> = data["interfaces"]
        .as_array()
        .unwrap()
        .iter()
        .map(|i| i["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["BIG_END", "SMALL_END"]);
    println!(
        "conrod page: {} of {n} nodes, {} triangles, {} modes equal to the file (float32)",
        stored.len(),
        crate::common::base64_block(data["triangles"].as_str().unwrap())
            .0
            .len()
            / 12,
        modes.len()
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// A headless Chromium on the PATH.
fn chromium() -> Option<&'static str> {
    [
        "chromium",
        "chromium-browser",
        "google-chrome",
        "google-chrome-stable",
    ]
    .into_iter()
    .find(|b| {
        Command::new(b)
            .arg("--version")
            .output()
            .is_ok_and(|o| o.status.success())
    })
}

/// Runs the browser headless on `url` with `args`; (stdout, stderr). `timeout` guards a hung
/// browser (not an assertion on time).
fn headless(browser: &str, url: &str, args: &[&str]) -> (String, String) {
    let o = Command::new("timeout")
        .args([
            "120",
            browser,
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
        ])
        .args(["--hide-scrollbars", "--window-size=1000,650"])
        .args([
            "--virtual-time-budget=3000",
            "--enable-logging=stderr",
            "--v=0",
        ])
        .args(args)
        .arg(url)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "{browser}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    (
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// The page's `<body …>` attribute `name`.
fn body_attribute(dom: &str, name: &str) -> Option<String> {
    let tag_start = dom.find("<body")?;
    let tag = &dom[tag_start..tag_start + dom[tag_start..].find('>')?];
    let at = tag.find(&format!("{name}=\""))? + name.len() + 2;
    Some(tag[at..at + tag[at..].find('"')?].to_string())
}

#[test]
fn the_page_draws_each_mode_in_headless_chromium_without_errors() {
    let Some(browser) = chromium() else {
        skipped_install(
            "the headless-browser check of view_html: no chromium on the PATH",
            "apt-get install chromium",
        );
        return;
    };
    let (body, html_path, dir) = conrod_page("browser");
    let url = |mode: usize| format!("file://{}#mode={mode}&t=0.25", html_path.display());
    let mut frames = Vec::new();
    for mode in [1, 7] {
        let (dom, log) = headless(browser, &url(mode), &["--dump-dom"]);
        let console: Vec<&str> = log.lines().filter(|l| l.contains(":CONSOLE")).collect();
        assert!(console.is_empty(), "console messages: {console:?}");
        assert_eq!(body_attribute(&dom, "data-errors"), None, "script errors");
        assert_eq!(body_attribute(&dom, "data-status").as_deref(), Some("ok"));
        assert_eq!(body_attribute(&dom, "data-mode"), Some(mode.to_string()));
        let drawn: usize = body_attribute(&dom, "data-drawn").unwrap().parse().unwrap();
        let hash = body_attribute(&dom, "data-frame").unwrap();
        println!("mode {mode}: {drawn} pixels drawn, frame hash {hash}");
        // The body covers a visible part of the canvas (700 × 650 px beside the side panel).
        assert!(drawn > 10_000, "{drawn} pixels drawn");
        frames.push(hash);
    }
    // Mode 1 of the free conrod is a rigid-body mode, mode 7 its first constraint mode.
    assert_eq!(body.modes.labels[0], file::ModeLabel::Rigid);
    assert_eq!(body.modes.labels[6], file::ModeLabel::Constraint);
    assert_ne!(
        frames[0], frames[1],
        "mode 7 draws the same pixels as mode 1"
    );
    let mut shots = Vec::new();
    for mode in [1, 7] {
        let png = dir.join(format!("mode{mode}.png"));
        let shot = format!("--screenshot={}", png.display());
        headless(browser, &url(mode), &[&shot]);
        let bytes = std::fs::read(&png).unwrap();
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
        shots.push(bytes);
    }
    assert_ne!(
        shots[0], shots[1],
        "the screenshots of modes 1 and 7 are equal"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
