//! The scatter plot of an area-against-error trade (`gbump sweep`, `gbump fit`): every point,
//! the Pareto front as a line, the paper's 10,000-25,000 GE band.

/// One point of the plot.
pub struct Dot {
    pub x: f64,
    pub y: f64,
    pub label: String,
    /// On the Pareto front (ringed and labelled, joined by the front's line).
    pub front: bool,
    /// The chosen point (filled red).
    pub chosen: bool,
}

pub fn scatter(points: &[Dot], title: &str, x_label: &str, y_label: &str) -> String {
    let (w, h, m) = (720.0, 440.0, 70.0);
    let (x0, x1) = (0.0, points.iter().map(|p| p.x).fold(1.0, f64::max) * 1.08);
    let (y0, y1) = (
        points.iter().map(|p| p.y).fold(0.0, f64::min).min(0.0) * 1.15,
        points.iter().map(|p| p.y).fold(0.01, f64::max) * 1.15,
    );
    let px = |x: f64| m + (x - x0) / (x1 - x0) * (w - 1.5 * m);
    let py = |y: f64| h - m - (y - y0) / (y1 - y0) * (h - 1.8 * m);
    let mut s = format!("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" font-family=\"sans-serif\" font-size=\"11\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n<text x=\"{}\" y=\"22\" font-size=\"14\" text-anchor=\"middle\">{}</text>\n", w / 2.0, esc(title));
    s += &format!("<line x1=\"{m}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"black\"/>\n<line x1=\"{m}\" y1=\"{}\" x2=\"{m}\" y2=\"{}\" stroke=\"black\"/>\n", h - m, w - 0.5 * m, h - m, h - m, 0.8 * m);
    for i in 0..=5 {
        let xv = x0 + (x1 - x0) * i as f64 / 5.0;
        let yv = y0 + (y1 - y0) * i as f64 / 5.0;
        s += &format!(
            "<text x=\"{:.1}\" y=\"{}\" text-anchor=\"middle\">{:.0}</text>\n",
            px(xv),
            h - m + 16.0,
            xv
        );
        s += &format!(
            "<text x=\"{}\" y=\"{:.1}\" text-anchor=\"end\">{:.3}</text>\n",
            m - 6.0,
            py(yv) + 4.0,
            yv
        );
    }
    s += &format!(
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n",
        w / 2.0,
        h - 22.0,
        esc(x_label)
    );
    s += &format!(
        "<text x=\"16\" y=\"{}\" transform=\"rotate(-90 16 {})\" text-anchor=\"middle\">{}</text>\n",
        h / 2.0,
        h / 2.0,
        esc(y_label)
    );
    // The paper's 10,000–25,000 GE estimate for the blend units, as a band.
    s += &format!(
        "<rect x=\"{:.1}\" y=\"{}\" width=\"{:.1}\" height=\"{}\" fill=\"#2a7\" opacity=\"0.08\"/>\n",
        px(10_000.0),
        0.8 * m,
        (px(25_000.0) - px(10_000.0)).max(0.0),
        h - 1.8 * m
    );
    s += &format!(
        "<text x=\"{:.1}\" y=\"{}\" fill=\"#2a7\">paper: 10k-25k GE</text>\n",
        px(10_000.0) + 4.0,
        0.8 * m + 12.0
    );
    let mut front: Vec<&Dot> = points.iter().filter(|p| p.front).collect();
    front.sort_by(|a, b| a.x.total_cmp(&b.x));
    let path: Vec<String> = front.iter().map(|p| format!("{:.1},{:.1}", px(p.x), py(p.y))).collect();
    s += &format!(
        "<polyline points=\"{}\" fill=\"none\" stroke=\"#c33\" stroke-width=\"1.5\"/>\n",
        path.join(" ")
    );
    for p in points {
        let (cx, cy) = (px(p.x), py(p.y));
        s += &format!(
            "<circle cx=\"{cx:.1}\" cy=\"{cy:.1}\" r=\"3.5\" fill=\"{}\"><title>{}</title></circle>\n",
            if p.chosen { "#c33" } else { "#246" },
            esc(&p.label)
        );
        if p.front {
            s += &format!("<circle cx=\"{cx:.1}\" cy=\"{cy:.1}\" r=\"7\" fill=\"none\" stroke=\"#c33\"/>\n<text x=\"{:.1}\" y=\"{:.1}\" font-size=\"9\">{}</text>\n", cx + 8.0, cy - 6.0, esc(&p.label));
        }
    }
    s + "</svg>\n"
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;")
}
