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
    let ticks: Vec<(f64, String, f64, String)> = (0..=5)
        .map(|i| {
            let xv = x0 + (x1 - x0) * i as f64 / 5.0;
            let yv = y0 + (y1 - y0) * i as f64 / 5.0;
            (px(xv), format!("{xv:.0}"), py(yv), format!("{yv:.3}"))
        })
        .collect();
    let mut s = axes((w, h, m), title, x_label, y_label, &ticks);
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
            crate::xml::escape(&p.label)
        );
        if p.front {
            s += &format!("<circle cx=\"{cx:.1}\" cy=\"{cy:.1}\" r=\"7\" fill=\"none\" stroke=\"#c33\"/>\n<text x=\"{:.1}\" y=\"{:.1}\" font-size=\"9\">{}</text>\n", cx + 8.0, cy - 6.0, crate::xml::escape(&p.label));
        }
    }
    s + "</svg>\n"
}

/// An SVG's head, title, axes, tick labels (x position and text, y position and text) and
/// axis names, for a `w`×`h` plot with margin `m`; the caller adds the marks and `</svg>`.
fn axes((w, h, m): (f64, f64, f64), title: &str, x_label: &str, y_label: &str, ticks: &[(f64, String, f64, String)]) -> String {
    let mut s = format!("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" font-family=\"sans-serif\" font-size=\"11\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n<text x=\"{}\" y=\"22\" font-size=\"14\" text-anchor=\"middle\">{}</text>\n", w / 2.0, crate::xml::escape(title));
    s += &format!("<line x1=\"{m}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"black\"/>\n<line x1=\"{m}\" y1=\"{}\" x2=\"{m}\" y2=\"{}\" stroke=\"black\"/>\n", h - m, w - 0.5 * m, h - m, h - m, 0.8 * m);
    for (x, xt, y, yt) in ticks {
        s += &format!("<text x=\"{x:.1}\" y=\"{}\" text-anchor=\"middle\">{xt}</text>\n", h - m + 16.0);
        s += &format!("<text x=\"{}\" y=\"{:.1}\" text-anchor=\"end\">{yt}</text>\n", m - 6.0, y + 4.0);
    }
    s += &format!(
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n",
        w / 2.0,
        h - 22.0,
        crate::xml::escape(x_label)
    );
    s += &format!(
        "<text x=\"16\" y=\"{}\" transform=\"rotate(-90 16 {})\" text-anchor=\"middle\">{}</text>\n",
        h / 2.0,
        h / 2.0,
        crate::xml::escape(y_label)
    );
    s
}

/// One series of a line plot: its label and its points in x order.
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
}

/// A line plot of `series` (each its own colour, dotted where its label says "dashed"), axes
/// from zero, a legend at the top right; `log2_x` spaces x by its logarithm (map sizes).
pub fn lines(series: &[Series], title: &str, x_label: &str, y_label: &str, log2_x: bool) -> String {
    const COLOURS: [&str; 6] = ["#246", "#c33", "#2a7", "#a5c", "#d80", "#555"];
    let (w, h, m) = (720.0, 440.0, 70.0);
    let fx = |x: f64| if log2_x { x.max(1e-12).log2() } else { x };
    let all = || series.iter().flat_map(|s| s.points.iter());
    let (x0, x1) = (
        all()
            .map(|p| fx(p.0))
            .fold(f64::INFINITY, f64::min)
            .min(if log2_x { f64::INFINITY } else { 0.0 }),
        all().map(|p| fx(p.0)).fold(f64::NEG_INFINITY, f64::max),
    );
    let (x0, x1) = if x1 > x0 { (x0, x1) } else { (x0 - 1.0, x0 + 1.0) };
    let y1 = all().map(|p| p.1).filter(|y| y.is_finite()).fold(1e-9, f64::max) * 1.1;
    let px = |x: f64| m + (fx(x) - x0) / (x1 - x0) * (w - 1.5 * m);
    let py = |y: f64| h - m - y.clamp(0.0, y1) / y1 * (h - 1.8 * m);
    let ticks: Vec<(f64, String, f64, String)> = (0..=5)
        .map(|i| {
            let t = x0 + (x1 - x0) * i as f64 / 5.0;
            let xv = if log2_x { t.exp2() } else { t };
            let yv = y1 * i as f64 / 5.0;
            (
                m + (t - x0) / (x1 - x0) * (w - 1.5 * m),
                format!("{xv:.0}"),
                py(yv),
                format!("{yv:.2}"),
            )
        })
        .collect();
    let mut s = axes((w, h, m), title, x_label, y_label, &ticks);
    for (i, se) in series.iter().enumerate() {
        let c = COLOURS[i % COLOURS.len()];
        let dash = if se.label.contains("dashed") {
            " stroke-dasharray=\"5 3\""
        } else {
            ""
        };
        let path: Vec<String> = se.points.iter().map(|p| format!("{:.1},{:.1}", px(p.0), py(p.1))).collect();
        s += &format!(
            "<polyline points=\"{}\" fill=\"none\" stroke=\"{c}\" stroke-width=\"1.5\"{dash}/>\n",
            path.join(" ")
        );
        for p in &se.points {
            s += &format!(
                "<circle cx=\"{:.1}\" cy=\"{:.1}\" r=\"2.5\" fill=\"{c}\"><title>{}: ({}, {:.3})</title></circle>\n",
                px(p.0),
                py(p.1),
                crate::xml::escape(&se.label),
                p.0,
                p.1
            );
        }
        s += &format!(
            "<text x=\"{}\" y=\"{}\" fill=\"{c}\">{}</text>\n",
            w - 1.5 * m - 150.0,
            0.8 * m + 14.0 * i as f64,
            crate::xml::escape(&se.label)
        );
    }
    s + "</svg>\n"
}
