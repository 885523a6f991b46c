//! A curve's pseudo-curvatures rendered: the text report and the SVG picture of the curve with
//! the osculating circles of κinf and κsup at every reported point.

use super::curvature::{CurveCurvature, SideRange};

impl CurveCurvature {
    /// A human-readable rendering.
    pub fn to_text(&self, exact: bool) -> String {
        let cut = |s: &str| -> String {
            if exact || s.chars().count() <= 60 {
                s.to_string()
            } else {
                format!("{}…", s.chars().take(60).collect::<String>())
            }
        };
        let vec = |v: &[String]| cut(&format!("({})", v.join(", ")));
        let mut out =
            String::from("differential characteristic functions D(t) = c + t·v1 + β·|t|^α·v2:\n");
        for d in &self.dcfs {
            match d {
                Err(e) => out += &format!("  {e}\n"),
                Ok(d) => {
                    out += &format!(
                        "  {}: {} (α = {}), λ1 = {}, λ2 = {}\n    c = {}, v1 = {}, v2 = {}\n    {}\n",
                        d.operator,
                        d.class,
                        d.alpha,
                        cut(&d.lambda1),
                        cut(&d.lambda2),
                        vec(&d.c),
                        vec(&d.v1),
                        vec(&d.v2),
                        d.case
                    );
                    for s in &d.starts {
                        out += &format!(
                            "    from {}: x1 = {}, x2 = {}, β = {}\n",
                            s.from,
                            cut(&s.x1),
                            cut(&s.x2),
                            s.beta
                                .as_deref()
                                .map_or_else(|| format!("{:.9}", s.beta_approx), cut)
                        );
                    }
                }
            }
        }
        let side = |s: &SideRange| {
            format!(
                "{} [{}, {}] via {}",
                s.side, s.kappa_inf, s.kappa_sup, s.through
            )
        };
        out += "pseudo-curvature [κinf, κsup] at the fixed points:\n";
        for (d, f) in self.dcfs.iter().zip(&self.fixed_points) {
            if let (Ok(d), false) = (d, f.is_empty()) {
                let parts: Vec<String> = f
                    .iter()
                    .filter(|s| s.samples > 0 || s.class != "finite")
                    .map(|s| format!("{} [{}, {}]", s.side, s.kappa_inf, s.kappa_sup))
                    .collect();
                out += &format!("  {}: {}\n", d.operator, parts.join("; "));
            }
        }
        out += "pseudo-curvature at dyadic points:\n";
        for p in &self.points {
            let pos: Vec<String> = p.position.iter().map(|x| format!("{x:.6}")).collect();
            out += &format!("  t = {} at ({})\n", p.t, pos.join(", "));
            for s in [&p.left, &p.right].into_iter().flatten() {
                out += &format!("    {}\n", side(s));
            }
        }
        out += &format!("  ({}; level {})\n", self.note, self.level);
        out
    }
}

impl CurveCurvature {
    /// An SVG picture (plane curves only): the curve, and at every reported point the osculating
    /// circles of κinf (green) and κsup (orange) on each side, centred on the side of β·V2.
    /// `None` for a curve in 3D.
    pub fn to_svg(&self) -> Option<String> {
        if self.polyline.first().is_none_or(|p| p.len() != 2) {
            return None;
        }
        let (mut x0, mut y0, mut x1, mut y1) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
        for p in &self.polyline {
            x0 = x0.min(p[0]);
            x1 = x1.max(p[0]);
            y0 = y0.min(p[1]);
            y1 = y1.max(p[1]);
        }
        let span = (x1 - x0).max(y1 - y0).max(1e-9);
        let (x0, y0, x1, y1) = (
            x0 - span / 2.0,
            y0 - span / 2.0,
            x1 + span / 2.0,
            y1 + span / 2.0,
        );
        let w = 800.0;
        let sc = w / (x1 - x0).max(y1 - y0);
        let tx = |x: f64| (x - x0) * sc;
        let ty = |y: f64| (y1 - y) * sc;
        let mut s = format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{w}\" viewBox=\"0 0 {w} {w}\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
        );
        let pts: Vec<String> = self
            .polyline
            .iter()
            .map(|p| format!("{:.3},{:.3}", tx(p[0]), ty(p[1])))
            .collect();
        s += &format!(
            "<polyline fill=\"none\" stroke=\"black\" stroke-width=\"1.5\" points=\"{}\"/>\n",
            pts.join(" ")
        );
        for p in &self.points {
            let (px, py) = (p.position[0], p.position[1]);
            for side in [&p.left, &p.right].into_iter().flatten() {
                let (Some(n), Some([blo, bhi])) = (side.normal, side.beta_range) else {
                    continue;
                };
                for (k, b, colour) in [
                    (
                        side.kappa_inf.0,
                        if blo.abs() < bhi.abs() { blo } else { bhi },
                        "#2a9d2a",
                    ),
                    (
                        side.kappa_sup.0,
                        if blo.abs() < bhi.abs() { bhi } else { blo },
                        "#e07b00",
                    ),
                ] {
                    if !(k.is_finite() && k > 0.0) {
                        continue;
                    }
                    let r = 1.0 / k;
                    let sgn = if b < 0.0 { -1.0 } else { 1.0 };
                    let (cx, cy) = (px + sgn * n[0] * r, py + sgn * n[1] * r);
                    s += &format!(
                        "<circle cx=\"{:.3}\" cy=\"{:.3}\" r=\"{:.3}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"1\"/>\n",
                        tx(cx),
                        ty(cy),
                        r * sc
                    );
                }
            }
            s += &format!(
                "<circle cx=\"{:.3}\" cy=\"{:.3}\" r=\"3\" fill=\"#c00\"><title>t = {}</title></circle>\n",
                tx(px),
                ty(py),
                p.t
            );
        }
        s += "</svg>\n";
        Some(s)
    }
}
