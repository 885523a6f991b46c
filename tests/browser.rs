//! The HTML report in a real browser: Debian's headless Chromium opens it, the page must log
//! nothing to the console (no script error, no warning), its layout is measured in the page itself,
//! and a screenshot is compared with a reference checked by eye (`tests/snapshots/report-*.png`).
//!
//! These tests need Chromium (`apt-get install chromium`, as `.ci/run` does), so they are marked
//! `#[ignore]`: `cargo test` lists them as ignored, and `.ci/run` runs them after the README's test
//! command with `cargo test --test browser -- --ignored`. Set `LACUNA_CHROMIUM` to use another
//! binary; `LACUNA_BLESS=1` rewrites the reference screenshots.

mod common;
use std::path::{Path, PathBuf};
use std::process::Command;

const WIDTH: u32 = 1280;

fn chromium() -> PathBuf {
    if let Ok(p) = std::env::var("LACUNA_CHROMIUM") {
        return PathBuf::from(p);
    }
    for name in ["chromium", "chromium-browser", "google-chrome"] {
        for dir in std::env::split_paths(&std::env::var_os("PATH").unwrap_or_default()) {
            let p = dir.join(name);
            if p.is_file() {
                return p;
            }
        }
    }
    panic!(
        "Chromium not found: install Debian's `chromium` (as .ci/run does) or set LACUNA_CHROMIUM"
    );
}

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("browser")
        .join(name);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs headless Chromium on `page` with extra arguments; returns (stdout, stderr).
fn browse(page: &Path, height: u32, extra: &[&str]) -> (String, String) {
    let profile = tempdir("profile");
    let out = Command::new(chromium())
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--hide-scrollbars",
            "--force-device-scale-factor=1",
            "--enable-logging=stderr",
            "--v=0",
            "--virtual-time-budget=5000",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .arg(format!("--window-size={WIDTH},{height}"))
        .args(extra)
        .arg(format!("file://{}", page.display()))
        .output()
        .expect("Chromium runs");
    assert!(
        out.status.success(),
        "Chromium failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn tempdir(what: &str) -> PathBuf {
    let n = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_nanos())
        .unwrap_or(0);
    let d = std::env::temp_dir().join(format!("lacuna-{what}-{}-{n}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn report(input: &str, level: &str) -> PathBuf {
    let dir = scratch(&input.replace([' ', '|'], "_"));
    let path = dir.join("report.html");
    let (code, _, err) = common::lacuna(&[
        "report",
        input,
        "--level",
        level,
        "--raster",
        "256",
        "--out",
        path.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    path
}

/// The console lines Chromium logged for the page (`INFO:CONSOLE…` on stderr).
fn console_lines(stderr: &str) -> Vec<&str> {
    stderr.lines().filter(|l| l.contains(":CONSOLE")).collect()
}

/// The script appended to a copy of the report: it measures the layout after load and writes one
/// line per element into the DOM, which `--dump-dom` prints. It logs nothing.
const PROBE: &str = r#"<script>
window.addEventListener('load', () => {
  const r = e => { const b = e.getBoundingClientRect();
    return [b.left, b.top, b.right, b.bottom].map(Math.round).join(' '); };
  const lines = ['page ' + document.documentElement.scrollWidth + ' ' + document.documentElement.scrollHeight];
  document.querySelectorAll('h1, h2, figure, table, svg, pre').forEach(e => {
    let label = e.tagName === 'H1' || e.tagName === 'H2' ? e.textContent.split(' ')[0] : '';
    if (e.tagName.toLowerCase() === 'svg') { const c = e.getBBox();
      label = Math.round(c.width) + ' ' + Math.round(c.height); }
    lines.push(e.tagName.toLowerCase() + ' ' + r(e) + ' ' + label);
  });
  // The report's new elements: legend entries against the face-type rows, the plots' axes and
  // tick labels, and every arrowhead of the type graph against every node circle (no vertex of
  // an arrowhead may lie inside a node).
  lines.push('legend ' + document.querySelectorAll('li.legend-entry').length + ' ' +
    Math.max(0, document.querySelectorAll('table.types tr').length - 1));
  document.querySelectorAll('svg.plot').forEach(p => lines.push('plot ' +
    p.querySelectorAll('g.axis').length + ' ' + p.querySelectorAll('text.tick').length + ' ' +
    p.querySelectorAll('line.fit').length + ' ' + p.querySelectorAll('text.equation').length));
  document.querySelectorAll('svg.curvature-plot').forEach(p => lines.push('kappa ' +
    p.querySelectorAll('g.kappa-left line').length + ' ' +
    p.querySelectorAll('g.kappa-right line').length + ' ' +
    p.querySelectorAll('.kappa-inf-marker').length));
  const nodes = [...document.querySelectorAll('circle.node')].map(c =>
    [c.cx.baseVal.value, c.cy.baseVal.value, c.r.baseVal.value]);
  let inside = 0, heads = 0;
  document.querySelectorAll('path.arrowhead').forEach(a => {
    heads++;
    const v = a.getAttribute('d').match(/-?[0-9.]+/g).map(Number);
    for (let i = 0; i + 1 < v.length; i += 2)
      for (const [x, y, r] of nodes)
        if (Math.hypot(v[i] - x, v[i + 1] - y) < r) inside++;
  });
  lines.push('arrows ' + heads + ' ' + document.querySelectorAll('path.edge, path.loop').length +
    ' ' + inside + ' ' + nodes.length);
  const out = document.createElement('pre');
  out.id = 'layout-probe';
  out.textContent = lines.join('\n');
  document.body.appendChild(out);
});
</script>"#;

#[derive(Debug)]
struct Boxed {
    tag: String,
    rect: [i64; 4],
    label: String,
}

/// The probe's lines about the report's elements: `legend ENTRIES TYPES`, one `plot AXES TICKS
/// FITS EQUATIONS` per plot, `arrows HEADS EDGES INSIDE NODES`, one `kappa LEFT RIGHT INFINITE`
/// per curvature-range plot (bars on each side, +∞ markers).
fn probe_lines(page: &Path) -> Vec<Vec<String>> {
    let html = std::fs::read_to_string(page).unwrap();
    let probed = page.with_file_name("probed.html");
    std::fs::write(&probed, html.replace("</body>", &format!("{PROBE}</body>"))).unwrap();
    let (dom, _) = browse(&probed, 1000, &["--dump-dom"]);
    let start = dom.find("id=\"layout-probe\">").expect("the probe ran") + 18;
    let text = &dom[start..start + dom[start..].find("</pre>").unwrap()];
    text.lines()
        .filter(|l| {
            ["legend ", "plot ", "arrows ", "kappa "]
                .iter()
                .any(|p| l.starts_with(p))
        })
        .map(|l| l.split(' ').map(str::to_string).collect())
        .collect()
}

/// The legend has one entry per face type; every plot has two axes, tick labels on both, the
/// fitted line and its equation; the type graph has an arrowhead per arrow, none inside a node.
fn check_elements(page: &Path, types: usize) {
    let lines = probe_lines(page);
    let find = |k: &str| lines.iter().filter(|l| l[0] == k).collect::<Vec<_>>();
    let n = |l: &Vec<String>, i: usize| l[i].parse::<usize>().unwrap();
    let legend = find("legend");
    assert_eq!(
        (n(legend[0], 1), n(legend[0], 2)),
        (types, types),
        "legend entries against types"
    );
    let plots = find("plot");
    assert_eq!(plots.len(), 3, "plots");
    for p in plots {
        assert_eq!(n(p, 1), 2, "two axes: {p:?}");
        assert!(n(p, 2) >= 6, "tick labels on both axes: {p:?}");
        assert_eq!(
            (n(p, 3), n(p, 4)),
            (1, 1),
            "the fitted line and its equation: {p:?}"
        );
    }
    let arrows = find("arrows");
    let a = arrows[0];
    assert_eq!(n(a, 4), types, "one node per type");
    assert!(
        n(a, 1) > 0 && n(a, 1) == n(a, 2),
        "an arrowhead per arrow: {a:?}"
    );
    assert_eq!(n(a, 3), 0, "arrowhead vertices inside node circles: {a:?}");
}

fn layout(page: &Path) -> (i64, i64, Vec<Boxed>) {
    let html = std::fs::read_to_string(page).unwrap();
    let probed = page.with_file_name("probed.html");
    std::fs::write(&probed, html.replace("</body>", &format!("{PROBE}</body>"))).unwrap();
    let (dom, _) = browse(&probed, 1000, &["--dump-dom"]);
    let start = dom.find("id=\"layout-probe\">").expect("the probe ran") + 18;
    let text = &dom[start..start + dom[start..].find("</pre>").unwrap()];
    let mut lines = text.lines();
    let page_line: Vec<i64> = lines
        .next()
        .unwrap()
        .split(' ')
        .skip(1)
        .map(|x| x.parse().unwrap())
        .collect();
    let boxes = lines
        .filter(|l| {
            !["legend ", "plot ", "arrows ", "kappa "]
                .iter()
                .any(|p| l.starts_with(p))
        })
        .map(|l| {
            let w: Vec<&str> = l.splitn(6, ' ').collect();
            Boxed {
                tag: w[0].to_string(),
                rect: [1, 2, 3, 4].map(|i| w[i].parse().unwrap()),
                label: w.get(5).unwrap_or(&"").to_string(),
            }
        })
        .collect();
    (page_line[0], page_line[1], boxes)
}

fn overlap(a: &[i64; 4], b: &[i64; 4]) -> bool {
    a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3]
}

fn check_layout(page: &Path, pictures: usize) -> i64 {
    let (width, height, boxes) = layout(page);
    assert!(
        width <= WIDTH as i64,
        "the page overflows horizontally: {width}px"
    );
    // Headings in the documented order, top to bottom.
    let headings: Vec<(&str, i64)> = boxes
        .iter()
        .filter(|b| b.tag == "h2")
        .map(|b| (b.label.as_str(), b.rect[1]))
        .collect();
    let order = [
        "Pictures",
        "Type",
        "Face",
        "Counts",
        "Limit",
        "Constraint",
        "Measures",
    ];
    let names: Vec<&str> = headings.iter().map(|h| h.0).collect();
    assert_eq!(names, order, "sections");
    assert!(
        headings.windows(2).all(|w| w[0].1 < w[1].1),
        "sections out of order: {headings:?}"
    );
    // Every element has a size and lies inside the page.
    for b in &boxes {
        let [l, t, r, bo] = b.rect;
        assert!(r > l && bo > t, "{} has no size: {:?}", b.tag, b.rect);
        assert!(
            l >= 0 && r <= WIDTH as i64,
            "{} sticks out of the page: {:?}",
            b.tag,
            b.rect
        );
    }
    // The pictures: one figure per level, pairwise disjoint, all between "Pictures" and "Type".
    let figures: Vec<&Boxed> = boxes.iter().filter(|b| b.tag == "figure").collect();
    assert_eq!(figures.len(), pictures);
    for (i, a) in figures.iter().enumerate() {
        for b in &figures[i + 1..] {
            assert!(!overlap(&a.rect, &b.rect), "figures overlap");
        }
        assert!(a.rect[1] > headings[0].1 && a.rect[3] < headings[1].1);
    }
    // The type graph is cropped to its nodes: no tall empty canvas before the next section.
    let graph = boxes
        .iter()
        .find(|b| b.tag == "svg" && b.rect[1] > headings[1].1 && b.rect[3] < headings[2].1)
        .expect("the type graph");
    assert!(
        headings[2].1 - graph.rect[3] < 80,
        "empty space below the type graph: {:?}",
        graph.rect
    );
    // … and inside it: the drawn content fills the canvas up to the margins.
    let content: Vec<i64> = graph.label.split(' ').map(|x| x.parse().unwrap()).collect();
    let (w, h) = (graph.rect[2] - graph.rect[0], graph.rect[3] - graph.rect[1]);
    assert!(
        w - content[0] <= 110 && h - content[1] <= 110,
        "the type graph's canvas {w}×{h} is much larger than its content {content:?}"
    );
    // Three plots in the measures section.
    let plots = boxes
        .iter()
        .filter(|b| b.tag == "svg" && b.rect[1] > headings[6].1)
        .count();
    assert_eq!(plots, 3, "plots in the measures section");
    height
}

/// Decodes an RGB(A) PNG into (width, height, grey levels).
fn decode(bytes: &[u8]) -> (usize, usize, Vec<u8>) {
    let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    let channels = info.color_type.samples();
    let grey = buf[..info.buffer_size()]
        .chunks(channels)
        .map(|p| {
            if channels >= 3 {
                ((p[0] as u32 * 30 + p[1] as u32 * 59 + p[2] as u32 * 11) / 100) as u8
            } else {
                p[0]
            }
        })
        .collect();
    (info.width as usize, info.height as usize, grey)
}

/// Mean grey level of every 16×16 block: robust to anti-aliasing, sensitive to layout.
fn blocks(w: usize, h: usize, g: &[u8]) -> Vec<f64> {
    let mut out = Vec::new();
    for by in 0..h / 16 {
        for bx in 0..w / 16 {
            let mut s = 0u32;
            for y in 0..16 {
                for x in 0..16 {
                    s += g[(by * 16 + y) * w + bx * 16 + x] as u32;
                }
            }
            out.push(s as f64 / 256.0);
        }
    }
    out
}

/// A screenshot of the page (`height` pixels, whole 16-pixel blocks) compared with its reference
/// block by block; `extra` adds Chromium flags (SwiftShader for a page with WebGL).
fn check_screenshot(page: &Path, name: &str, height: u32, extra: &[&str]) {
    let shot = page.with_file_name("screenshot.png");
    let flag = format!("--screenshot={}", shot.display());
    let args: Vec<&str> = std::iter::once(flag.as_str())
        .chain(extra.iter().copied())
        .collect();
    let (_, stderr) = browse(page, height, &args);
    // Taking the screenshot of a WebGL canvas reads its pixels, and the driver logs a
    // performance note about it; nothing else may be logged.
    let console: Vec<&str> = console_lines(&stderr)
        .into_iter()
        .filter(|l| !l.contains("GPU stall due to ReadPixels"))
        .collect();
    assert!(console.is_empty(), "console: {console:?}");
    let bytes = std::fs::read(&shot).unwrap();
    let (w, h, grey) = decode(&bytes);
    assert_eq!((w, h), (WIDTH as usize, height as usize));
    // Not blank: the pictures are drawn (dark pixels) and most of the page is background.
    let dark = grey.iter().filter(|&&v| v < 128).count();
    assert!(dark > w * h / 200, "the screenshot is nearly blank");
    let reference =
        Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("tests/snapshots/report-{name}.png"));
    if std::env::var_os("LACUNA_BLESS").is_some() {
        std::fs::write(&reference, &bytes).unwrap();
        return;
    }
    let want = std::fs::read(&reference).unwrap_or_else(|_| {
        panic!(
            "no reference {}: look at {} and bless it with LACUNA_BLESS=1",
            reference.display(),
            shot.display()
        )
    });
    let (rw, rh, rgrey) = decode(&want);
    assert_eq!(
        (rw, rh),
        (w, h),
        "page size changed; see {}",
        shot.display()
    );
    let (a, b) = (blocks(w, h, &grey), blocks(rw, rh, &rgrey));
    let differing = a
        .iter()
        .zip(&b)
        .filter(|(x, y)| (*x - *y).abs() > 24.0)
        .count();
    assert!(
        differing * 100 <= a.len(),
        "{differing} of {} blocks differ from the reference: compare {} with {}",
        a.len(),
        shot.display(),
        reference.display()
    );
}

fn check_report(input: &str, level: u32, name: &str, types: usize) {
    let page = report(input, &level.to_string());
    // No console output at all while loading (errors, warnings or logs).
    let (_, stderr) = browse(&page, 1000, &["--dump-dom"]);
    let console = console_lines(&stderr);
    assert!(console.is_empty(), "console output: {console:#?}");
    let height = check_layout(&page, level as usize + 1);
    check_elements(&page, types);
    // Screenshot of the whole page, rounded up to whole 16-pixel blocks.
    let height = (height as u32).div_ceil(16) * 16;
    check_screenshot(&page, name, height, &[]);
}

#[test]
#[ignore = "needs Debian's chromium; .ci/run runs it with --ignored"]
fn f0_report_in_chromium() {
    check_report("F0", 3, "F0", 1);
}

#[test]
#[ignore = "needs Debian's chromium; .ci/run runs it with --ignored"]
fn four_type_report_in_chromium() {
    check_report("triangle-C2", 2, "triangle-C2", 4);
}

#[test]
#[ignore = "needs Debian's chromium; .ci/run runs it with --ignored"]
fn fifteen_type_graph_in_chromium() {
    // A delayed face of 15 types: every arrowhead still lies outside every node circle.
    let face = "B2 C3 B2 C2 B3 | C2 B2 C2 | A3 | 2";
    let page = report(face, "1");
    check_elements(&page, 15);
}

#[test]
#[ignore = "needs Debian's chromium; .ci/run runs it with --ignored"]
fn automaton_report_in_chromium() {
    // The report of an automaton (issues #14, #16, #32): no console output; the sections in the
    // order of every report (the pictures first, after the verdict);
    // every element inside the page; the box-counting plot with its fit and equation; the
    // curvature-range plot with its bars. Hand count for the cubic de Casteljau curve (I = 2
    // operators): the parameters are 0, 1/2, 1 and j/8 for j = 1, 2, 3, 5, 6, 7; a left side at
    // every t > 0 (8) and a right side at every t < 1 (8); the class is finite everywhere
    // (α = 2 for de Casteljau operators), so 8 bars on each side and no +∞ marker.
    let page = report("de-casteljau-cubic", "3");
    let (_, stderr) = browse(&page, 1000, &["--dump-dom"]);
    let console = console_lines(&stderr);
    assert!(console.is_empty(), "console output: {console:#?}");
    let (width, _, boxes) = layout(&page);
    assert!(width <= WIDTH as i64, "the page overflows: {width}px");
    let names: Vec<&str> = boxes
        .iter()
        .filter(|b| b.tag == "h2")
        .map(|b| b.label.as_str())
        .collect();
    assert_eq!(
        names,
        [
            "Pictures",
            "Solver",
            "Contraction",
            "Operators",
            "Dimension",
            "Pseudo-curvature",
            "Levels",
            "Input"
        ],
        "sections"
    );
    for b in &boxes {
        let [l, t, r, bo] = b.rect;
        assert!(r > l && bo > t, "{} has no size: {:?}", b.tag, b.rect);
        assert!(
            l >= 0 && r <= WIDTH as i64,
            "{} sticks out: {:?}",
            b.tag,
            b.rect
        );
    }
    assert_eq!(
        boxes.iter().filter(|b| b.tag == "figure").count(),
        4,
        "levels 0–3"
    );
    let lines = probe_lines(&page);
    let n = |l: &Vec<String>, i: usize| l[i].parse::<usize>().unwrap();
    let plots: Vec<_> = lines.iter().filter(|l| l[0] == "plot").collect();
    assert_eq!(
        plots.len(),
        2,
        "the box-counting and curvature plots: {plots:?}"
    );
    for p in &plots {
        assert_eq!(n(p, 1), 2, "two axes: {p:?}");
        assert!(n(p, 2) >= 6, "tick labels on both axes: {p:?}");
    }
    assert_eq!(
        (n(plots[0], 3), n(plots[0], 4)),
        (1, 1),
        "the box fit: {:?}",
        plots[0]
    );
    let kappa: Vec<_> = lines.iter().filter(|l| l[0] == "kappa").collect();
    assert_eq!(kappa.len(), 1);
    assert_eq!((n(kappa[0], 1), n(kappa[0], 2), n(kappa[0], 3)), (8, 8, 0));
    // The whole page against the reference looked at by eye (issue #32).
    let (_, height, _) = layout(&page);
    check_screenshot(
        &page,
        "de-casteljau-cubic",
        (height as u32).div_ceil(16) * 16,
        &[],
    );
}

#[test]
#[ignore = "needs Debian's chromium; .ci/run runs it with --ignored"]
fn the_console_check_can_fail() {
    // The same probe on a page with a script error and a log line must see both.
    let dir = scratch("bad");
    let page = dir.join("bad.html");
    std::fs::write(
        &page,
        "<html><body><script>console.log('x'); missing();</script></body></html>",
    )
    .unwrap();
    let (_, stderr) = browse(&page, 200, &["--dump-dom"]);
    let console = console_lines(&stderr);
    assert_eq!(console.len(), 2, "{console:#?}");
    assert!(console[1].contains("Uncaught ReferenceError"));
}

/// The volume report's WebGL view in Chromium: the script logs nothing, marks the canvas ready,
/// draws the solid (part of the canvas covered, in several shades), and a mouse drag turns it
/// (the pixels change). The probe reads the canvas back with `readPixels` and writes its counts
/// into the DOM, which `--dump-dom` prints.
#[test]
#[ignore = "needs Debian's chromium; .ci/run runs it with --ignored"]
fn volume_report_webgl_view_in_chromium() {
    let dir = scratch("volume-report");
    let page = dir.join("report.html");
    let (code, _, err) = common::lacuna(&[
        "report",
        "tetrahedron-B2",
        "--level",
        "1",
        "--out",
        page.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let html = std::fs::read_to_string(&page).unwrap();
    let probe = r#"<script>
window.addEventListener('load', () => {
  const cv = document.getElementById('solid3d');
  const gl = cv.getContext('webgl', {preserveDrawingBuffer: true});
  const lines = ['ready ' + cv.getAttribute('data-ready') + ' ' + cv.getAttribute('data-error')];
  const read = () => { const px = new Uint8Array(4 * cv.width * cv.height);
    gl.readPixels(0, 0, cv.width, cv.height, gl.RGBA, gl.UNSIGNED_BYTE, px); return px; };
  const a = read();
  let cover = 0; const shades = new Set();
  for (let i = 0; i < a.length; i += 4)
    if (a[i] < 250 || a[i + 1] < 250 || a[i + 2] < 250) { cover++; shades.add(a[i] + ',' + a[i + 1] + ',' + a[i + 2]); }
  lines.push('cover ' + cover + ' ' + cv.width * cv.height + ' ' + shades.size);
  const at = (type, x, y) => new MouseEvent(type, {clientX: x, clientY: y, bubbles: true});
  cv.dispatchEvent(at('mousedown', 100, 100));
  window.dispatchEvent(at('mousemove', 160, 130));
  window.dispatchEvent(at('mouseup', 160, 130));
  const b = read();
  let changed = 0;
  for (let i = 0; i < a.length; i += 4) if (a[i] !== b[i] || a[i + 1] !== b[i + 1] || a[i + 2] !== b[i + 2]) changed++;
  lines.push('changed ' + changed);
  const out = document.createElement('pre'); out.id = 'webgl-probe'; out.textContent = lines.join('\n');
  document.body.appendChild(out);
});
</script>"#;
    let probed = dir.join("probed.html");
    std::fs::write(&probed, html.replace("</body>", &format!("{probe}</body>"))).unwrap();
    // Headless Chromium has no GPU: WebGL runs on SwiftShader, which it wants asked for.
    let (dom, stderr) = browse(&probed, 900, &["--dump-dom", "--enable-unsafe-swiftshader"]);
    // The probe's own `readPixels` makes the driver log a performance note; nothing else may
    // be logged.
    let console: Vec<&str> = console_lines(&stderr)
        .into_iter()
        .filter(|l| !l.contains("GPU stall due to ReadPixels"))
        .collect();
    assert!(console.is_empty(), "console: {console:?}");
    let text = &dom[dom.find("id=\"webgl-probe\">").expect("the probe ran") + 17..];
    let text = &text[..text.find("</pre>").unwrap()];
    let lines: Vec<Vec<&str>> = text.lines().map(|l| l.split(' ').collect()).collect();
    assert_eq!(lines[0], ["ready", "1", "null"], "{text}");
    let n = |i: usize, k: usize| lines[i][k].parse::<u64>().unwrap();
    let (cover, all, shades) = (n(1, 1), n(1, 2), n(1, 3));
    assert!(cover * 20 > all && cover * 20 < all * 19, "{text}");
    assert!(shades > 3, "{text}");
    assert!(n(2, 1) > all / 100, "a drag turns the solid: {text}");
    // The whole page, WebGL view included, against the reference looked at by eye (issue #32).
    let (width, height, _) = layout(&page);
    assert!(width <= WIDTH as i64, "the page overflows: {width}px");
    check_screenshot(
        &page,
        "tetrahedron-B2",
        (height as u32).div_ceil(16) * 16,
        &["--enable-unsafe-swiftshader"],
    );
}
