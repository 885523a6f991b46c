//! Pictures of a volume's solid (THEORY §10): a shaded PNG (own rasterizer with a depth buffer and
//! Lambert shading), an SVG projection (triangles facing the viewer, far to near), and a small
//! WebGL viewer for the HTML report (inlined, no external script; drag to rotate).
//!
//! All three draw the checked mesh ([`Part`]s in millimetres) in one orthographic view: looking
//! down on the solid from the front right, so that three sides of a cube show.

use crate::export::html::esc;
use crate::export::palette::{type_colour, Rgb};
use crate::mesh::Part;
use std::fmt::Write as _;
use std::io::{self, Write};

type V3 = [f64; 3];

fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn unit(a: V3) -> V3 {
    let n = dot(a, a).sqrt();
    if n > 0.0 {
        [a[0] / n, a[1] / n, a[2] / n]
    } else {
        a
    }
}

/// The view: screen right, screen up, and the direction from the eye into the picture.
struct View {
    right: V3,
    up: V3,
    into: V3,
    centre: V3,
    radius: f64,
    /// Half the side of the square the picture shows, in the solid's units.
    half: f64,
}

impl View {
    fn of(parts: &[Part]) -> View {
        let into = unit([-0.55, 0.75, -0.45]);
        let right = unit(cross(into, [0.0, 0.0, 1.0]));
        let up = cross(right, into);
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for p in parts {
            for v in &p.vertices {
                for k in 0..3 {
                    lo[k] = lo[k].min(f64::from(v[k]));
                    hi[k] = hi[k].max(f64::from(v[k]));
                }
            }
        }
        let centre = [0, 1, 2].map(|k| (lo[k] + hi[k]) / 2.0);
        // The farthest vertex from the centre: the solid fits the picture in every rotation.
        let radius = parts
            .iter()
            .flat_map(|p| p.vertices.iter())
            .map(|v| {
                let d = sub(v.map(f64::from), centre);
                dot(d, d).sqrt()
            })
            .fold(1e-9, f64::max);
        View {
            right,
            up,
            into,
            centre,
            radius,
            half: 1.05 * radius,
        }
    }

    /// The view of a still picture: [`View::of`] re-centred on the solid's outline in this view
    /// and scaled so that the outline's larger side fills 92 % of the picture (a rotating view
    /// keeps [`View::of`], which holds the solid in every rotation).
    fn framed(parts: &[Part]) -> View {
        let mut v = View::of(parts);
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in parts.iter().flat_map(|p| p.vertices.iter()) {
            let d = sub(p.map(f64::from), v.centre);
            for (k, axis) in [v.right, v.up].iter().enumerate() {
                lo[k] = lo[k].min(dot(d, *axis));
                hi[k] = hi[k].max(dot(d, *axis));
            }
        }
        if lo[0] > hi[0] {
            return v;
        }
        let (mx, my) = ((lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0);
        v.centre = [0, 1, 2].map(|k| v.centre[k] + mx * v.right[k] + my * v.up[k]);
        v.half = ((hi[0] - lo[0]).max(hi[1] - lo[1]) / 2.0 / 0.92).max(1e-9);
        v
    }

    /// Screen position in [0, size]² (y down) and depth (larger is farther).
    fn project(&self, p: V3, size: f64) -> (f64, f64, f64) {
        let d = sub(p, self.centre);
        let s = size / (2.0 * self.half);
        (
            size / 2.0 + dot(d, self.right) * s,
            size / 2.0 - dot(d, self.up) * s,
            dot(d, self.into),
        )
    }

    /// Lambert shade of a face with outward normal `n`: ambient, a key light above the viewer's
    /// left shoulder and a weaker fill light from the right, so that no side facing the viewer
    /// goes dark (the three sides of a cube in view get three distinct, readable shades).
    fn shade(&self, n: V3) -> f64 {
        let towards = |a: f64, b: f64| {
            unit([
                -self.into[0] + a * self.up[0] + b * self.right[0],
                -self.into[1] + a * self.up[1] + b * self.right[1],
                -self.into[2] + a * self.up[2] + b * self.right[2],
            ])
        };
        let (key, fill) = (towards(1.1, -0.5), towards(-0.2, 0.9));
        let n = unit(n);
        (0.42 + 0.5 * dot(n, key).max(0.0) + 0.28 * dot(n, fill).max(0.0)).min(1.0)
    }
}

/// The colour of the solid.
fn base() -> Rgb {
    type_colour(6)
}

fn shaded(c: Rgb, s: f64) -> Rgb {
    c.map(|x| (f64::from(x) * s).round().clamp(0.0, 255.0) as u8)
}

fn triangles(parts: &[Part]) -> impl Iterator<Item = [V3; 3]> + '_ {
    parts.iter().flat_map(|p| {
        p.triangles
            .iter()
            .map(move |t| t.map(|v| p.vertices[v as usize].map(f64::from)))
    })
}

/// Writes the solid as a shaded PNG of `size × size` pixels (white or transparent background).
pub fn write_volume_png<W: Write>(
    parts: &[Part],
    size: u32,
    transparent: bool,
    out: W,
) -> io::Result<()> {
    let view = View::framed(parts);
    // Supersampled, then averaged: smooth edges without a coverage rasterizer.
    let ss: u32 = if size <= 1400 { 3 } else { 1 };
    let n = (size * ss) as usize;
    let mut depth = vec![f64::INFINITY; n * n];
    let mut colour: Vec<Option<Rgb>> = vec![None; n * n];
    let c = base();
    for t in triangles(parts) {
        let normal = cross(sub(t[1], t[0]), sub(t[2], t[0]));
        let rgb = shaded(c, view.shade(normal));
        let q = t.map(|p| view.project(p, n as f64));
        let area = (q[1].0 - q[0].0) * (q[2].1 - q[0].1) - (q[2].0 - q[0].0) * (q[1].1 - q[0].1);
        if area.abs() < 1e-12 {
            continue;
        }
        let x0 = q
            .iter()
            .map(|p| p.0)
            .fold(f64::INFINITY, f64::min)
            .floor()
            .max(0.0) as usize;
        let x1 = (q
            .iter()
            .map(|p| p.0)
            .fold(f64::NEG_INFINITY, f64::max)
            .ceil() as usize)
            .min(n - 1);
        let y0 = q
            .iter()
            .map(|p| p.1)
            .fold(f64::INFINITY, f64::min)
            .floor()
            .max(0.0) as usize;
        let y1 = (q
            .iter()
            .map(|p| p.1)
            .fold(f64::NEG_INFINITY, f64::max)
            .ceil() as usize)
            .min(n - 1);
        for y in y0..=y1 {
            for x in x0..=x1 {
                let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
                let w = |a: (f64, f64, f64), b: (f64, f64, f64)| {
                    ((b.0 - a.0) * (py - a.1) - (px - a.0) * (b.1 - a.1)) / area
                };
                let (w0, w1, w2) = (w(q[1], q[2]), w(q[2], q[0]), w(q[0], q[1]));
                if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                    continue;
                }
                let z = w0 * q[0].2 + w1 * q[1].2 + w2 * q[2].2;
                let i = y * n + x;
                if z < depth[i] {
                    depth[i] = z;
                    colour[i] = Some(rgb);
                }
            }
        }
    }
    let s = size as usize;
    let ssu = ss as usize;
    let mut data = vec![0u8; s * s * 4];
    for y in 0..s {
        for x in 0..s {
            let (mut acc, mut cover) = ([0u32; 3], 0u32);
            for dy in 0..ssu {
                for dx in 0..ssu {
                    let bg = if transparent { None } else { Some([255u8; 3]) };
                    if let Some(c) = colour[(y * ssu + dy) * n + x * ssu + dx].or(bg) {
                        for k in 0..3 {
                            acc[k] += u32::from(c[k]);
                        }
                        cover += 1;
                    }
                }
            }
            let o = (y * s + x) * 4;
            for k in 0..3 {
                if let Some(v) = acc[k].checked_div(cover) {
                    data[o + k] = v as u8;
                }
            }
            data[o + 3] = (255 * cover / (ss * ss)) as u8;
        }
    }
    let mut enc = png::Encoder::new(out, size, size);
    enc.set_color(png::ColorType::Rgba);
    enc.set_depth(png::BitDepth::Eight);
    let mut w = enc.write_header().map_err(io::Error::other)?;
    w.write_image_data(&data).map_err(io::Error::other)?;
    w.finish().map_err(io::Error::other)
}

/// The SVG projection as a string: the triangles facing the viewer, drawn far to near, each
/// filled with its Lambert shade (and stroked with it, so that no seam shows between them).
pub fn volume_svg(parts: &[Part], size: u32) -> String {
    let view = View::framed(parts);
    let c = base();
    // (farthest depth, screen corners, shade) of each triangle facing the viewer.
    type Flat = (f64, [(f64, f64); 3], Rgb);
    let mut tris: Vec<Flat> = Vec::new();
    for t in triangles(parts) {
        let normal = cross(sub(t[1], t[0]), sub(t[2], t[0]));
        if dot(normal, view.into) >= 0.0 {
            continue;
        }
        let q = t.map(|p| view.project(p, f64::from(size)));
        let far = q.iter().map(|p| p.2).fold(f64::NEG_INFINITY, f64::max);
        tris.push((far, q.map(|p| (p.0, p.1)), shaded(c, view.shade(normal))));
    }
    tris.sort_by(|a, b| b.0.total_cmp(&a.0));
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{size}\" height=\"{size}\" viewBox=\"0 0 {size} {size}\">\n<rect width=\"{size}\" height=\"{size}\" fill=\"#ffffff\"/>\n"
    );
    for (_, q, rgb) in &tris {
        let hex = format!("#{:02x}{:02x}{:02x}", rgb[0], rgb[1], rgb[2]);
        let _ = writeln!(
            s,
            "<polygon points=\"{:.2},{:.2} {:.2},{:.2} {:.2},{:.2}\" fill=\"{hex}\" stroke=\"{hex}\" stroke-width=\"0.4\" stroke-linejoin=\"round\"/>",
            q[0].0, q[0].1, q[1].0, q[1].1, q[2].0, q[2].1
        );
    }
    s.push_str("</svg>\n");
    s
}

/// Writes the SVG projection.
pub fn write_volume_svg<W: Write>(parts: &[Part], size: u32, mut out: W) -> io::Result<()> {
    out.write_all(volume_svg(parts, size).as_bytes())?;
    out.flush()
}

/// An HTML fragment with a WebGL view of the solid: a canvas and an inline script holding the
/// triangles (positions centred and scaled to the unit ball). Drag to rotate. The script sets
/// `data-ready="1"` on the canvas once the first frame is drawn, or `data-error` with the reason.
pub fn volume_viewer(parts: &[Part]) -> String {
    volume_viewer_with_id(parts, "solid3d")
}

/// [`volume_viewer`] with the canvas named `id` (letters, digits, `-` and `_`; anything else is
/// dropped), so that several views can share a page, as the cells of a notebook do.
pub fn volume_viewer_with_id(parts: &[Part], id: &str) -> String {
    let id: String = id
        .chars()
        .filter(|c| c.is_ascii_alphanumeric() || *c == '-' || *c == '_')
        .collect();
    let view = View::of(parts);
    let mut pos = String::new();
    for t in triangles(parts) {
        for p in t {
            let d = sub(p, view.centre);
            let _ = write!(
                pos,
                "{:.4},{:.4},{:.4},",
                d[0] / view.radius,
                d[1] / view.radius,
                d[2] / view.radius
            );
        }
    }
    let c = base();
    format!(
        r#"<canvas id="{id}" width="560" height="560" style="border:1px solid #ccc;cursor:grab" title="drag to rotate"></canvas>
<script>
(function () {{
  var cv = document.getElementById('{id}');
  try {{
    var P = new Float32Array([{pos}]);
    var gl = cv.getContext('webgl', {{preserveDrawingBuffer: true}});
    if (!gl) {{ cv.setAttribute('data-error', 'no WebGL'); return; }}
    var N = new Float32Array(P.length);
    for (var i = 0; i < P.length; i += 9) {{
      var ux = P[i+3]-P[i], uy = P[i+4]-P[i+1], uz = P[i+5]-P[i+2];
      var vx = P[i+6]-P[i], vy = P[i+7]-P[i+1], vz = P[i+8]-P[i+2];
      var nx = uy*vz-uz*vy, ny = uz*vx-ux*vz, nz = ux*vy-uy*vx;
      var l = Math.sqrt(nx*nx+ny*ny+nz*nz) || 1;
      for (var k = 0; k < 9; k += 3) {{ N[i+k] = nx/l; N[i+k+1] = ny/l; N[i+k+2] = nz/l; }}
    }}
    function sh(type, src) {{
      var s = gl.createShader(type); gl.shaderSource(s, src); gl.compileShader(s);
      if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
      return s;
    }}
    var prog = gl.createProgram();
    gl.attachShader(prog, sh(gl.VERTEX_SHADER,
      'attribute vec3 p; attribute vec3 n; uniform mat3 r; varying float s;' +
      'void main() {{ vec3 q = r * p; vec3 m = r * n;' +
      ' s = 0.3 + 0.7 * max(dot(normalize(m), normalize(vec3(-0.4, 0.6, 1.0))), 0.0);' +
      ' gl_Position = vec4(q.x * 0.9, q.y * 0.9, -q.z * 0.5, 1.0); }}'));
    gl.attachShader(prog, sh(gl.FRAGMENT_SHADER,
      'precision mediump float; varying float s;' +
      'void main() {{ gl_FragColor = vec4(vec3({r:.4}, {g:.4}, {b:.4}) * s, 1.0); }}'));
    gl.linkProgram(prog);
    if (!gl.getProgramParameter(prog, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(prog));
    gl.useProgram(prog);
    function buf(data, name) {{
      var b = gl.createBuffer(); gl.bindBuffer(gl.ARRAY_BUFFER, b);
      gl.bufferData(gl.ARRAY_BUFFER, data, gl.STATIC_DRAW);
      var a = gl.getAttribLocation(prog, name); gl.enableVertexAttribArray(a);
      gl.vertexAttribPointer(a, 3, gl.FLOAT, false, 0, 0);
    }}
    buf(P, 'p'); buf(N, 'n');
    var ur = gl.getUniformLocation(prog, 'r');
    var yaw = -0.6, pitch = -1.0;
    function draw() {{
      var cy = Math.cos(yaw), sy = Math.sin(yaw), cp = Math.cos(pitch), sp = Math.sin(pitch);
      // Turn about z by yaw, then about the screen's x axis by pitch (column-major).
      var m = [cy, sy*cp, sy*sp, -sy, cy*cp, cy*sp, 0, -sp, cp];
      gl.uniformMatrix3fv(ur, false, new Float32Array(m));
      gl.viewport(0, 0, cv.width, cv.height);
      gl.clearColor(1, 1, 1, 1); gl.enable(gl.DEPTH_TEST);
      gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
      gl.drawArrays(gl.TRIANGLES, 0, P.length / 3);
    }}
    var drag = null;
    cv.addEventListener('mousedown', function (e) {{ drag = [e.clientX, e.clientY]; }});
    window.addEventListener('mouseup', function () {{ drag = null; }});
    window.addEventListener('mousemove', function (e) {{
      if (!drag) return;
      yaw += (e.clientX - drag[0]) * 0.01; pitch += (e.clientY - drag[1]) * 0.01;
      drag = [e.clientX, e.clientY]; draw();
    }});
    draw();
    cv.setAttribute('data-ready', '1');
  }} catch (err) {{ cv.setAttribute('data-error', String(err)); }}
}})();
</script>
"#,
        r = f64::from(c[0]) / 255.0,
        g = f64::from(c[1]) / 255.0,
        b = f64::from(c[2]) / 255.0,
    )
}

/// The HTML report of a volume, in the layout of every report (`crate::export::html::page_start`):
/// the title, the verdict (`ok`, its word, what it covers), the pictures — the WebGL view and the
/// SVG projection — then what was checked (as text) and the exact solid table.
pub fn volume_report_html(
    name: &str,
    verdict: (bool, &str, &str),
    sections: &[(&str, String)],
    parts: &[Part],
) -> String {
    let mut h = crate::export::html::page_start(name);
    h += &crate::export::html::verdict_line(verdict.0, verdict.1, verdict.2);
    let _ = write!(
        h,
        "<h2>Pictures</h2>\n<p>The solid (drag to rotate), and its projection.</p>\n{}\n{}\n",
        volume_viewer(parts),
        volume_svg(parts, 480)
    );
    for (head, text) in sections {
        let _ = write!(h, "<h2>{}</h2>\n<pre>{}</pre>\n", esc(head), esc(text));
    }
    h += "</body></html>\n";
    h
}
