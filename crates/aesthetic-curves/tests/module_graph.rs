//! The library's modules form no cycle (docs/architecture.md): no module uses, directly or
//! through others, a module that uses it back. The graph is read from the sources (a module
//! is `src/name.rs` or the files of `src/name/`): every `crate::name` outside comments and
//! outside the inline `#[cfg(test)]` module.

use std::collections::{BTreeMap, BTreeSet};

fn graph() -> BTreeMap<String, BTreeSet<String>> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/src");
    let mut names = BTreeSet::new();
    let mut texts = Vec::new();
    // A module is `src/name.rs` or a folder `src/name/` (all its files count as it).
    for entry in std::fs::read_dir(dir).expect("src") {
        let path = entry.expect("entry").path();
        let name = path.file_stem().unwrap().to_string_lossy().to_string();
        if path.is_dir() {
            names.insert(name.clone());
            for f in std::fs::read_dir(&path).expect("module folder") {
                let f = f.expect("entry").path();
                if f.extension().is_some_and(|e| e == "rs") {
                    texts.push((name.clone(), std::fs::read_to_string(&f).expect("read")));
                }
            }
        } else if path.extension().is_some_and(|e| e == "rs") && name != "lib" {
            names.insert(name.clone());
            texts.push((name, std::fs::read_to_string(&path).expect("read")));
        }
    }
    let mut out: BTreeMap<String, BTreeSet<String>> =
        names.iter().map(|n| (n.clone(), BTreeSet::new())).collect();
    for (name, text) in texts {
        let body = match text.find("#[cfg(test)]\nmod tests") {
            Some(i) => &text[..i],
            None => &text[..],
        };
        let mut uses = BTreeSet::new();
        for line in body.lines() {
            let code = line.trim_start();
            if code.starts_with("//") {
                continue;
            }
            let mut rest = code;
            while let Some(i) = rest.find("crate::") {
                rest = &rest[i + 7..];
                let ident: String = rest
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                if names.contains(&ident) && ident != name {
                    uses.insert(ident);
                }
            }
        }
        out.get_mut(&name).expect("named above").extend(uses);
    }
    out
}

#[test]
fn modules_form_no_cycle() {
    let g = graph();
    assert!(g.len() > 15, "read {} modules", g.len());
    // Depth-first search with colours; a grey node reached again closes a cycle.
    fn visit(
        n: &str,
        g: &BTreeMap<String, BTreeSet<String>>,
        colour: &mut BTreeMap<String, u8>,
        path: &mut Vec<String>,
    ) -> Option<Vec<String>> {
        colour.insert(n.to_string(), 1);
        path.push(n.to_string());
        for m in &g[n] {
            match colour.get(m.as_str()).copied().unwrap_or(0) {
                1 => {
                    let start = path.iter().position(|p| p == m).unwrap();
                    let mut cycle = path[start..].to_vec();
                    cycle.push(m.clone());
                    return Some(cycle);
                }
                0 => {
                    if let Some(c) = visit(m, g, colour, path) {
                        return Some(c);
                    }
                }
                _ => {}
            }
        }
        path.pop();
        colour.insert(n.to_string(), 2);
        None
    }
    let mut colour = BTreeMap::new();
    for n in g.keys() {
        if colour.get(n.as_str()).copied().unwrap_or(0) == 0 {
            if let Some(c) = visit(n, &g, &mut colour, &mut Vec::new()) {
                panic!("module cycle: {}", c.join(" -> "));
            }
        }
    }
}

#[test]
fn the_reader_sees_real_edges() {
    // The check above can only fail if the graph has edges: two known ones.
    let g = graph();
    assert!(g["pseudo_spline"].contains("pseudo_table"));
    assert!(g["approx"].contains("approx_table"));
    assert!(g["approx"].contains("nurbs") && !g["nurbs"].contains("approx"));
    // A module in a folder (lac/) is read too.
    assert!(g["approx"].contains("lac") && g["lac"].contains("quadrature"));
}

/// The layers of docs/architecture.md, bottom up: a module may use modules of its own layer
/// or below, never above.
const LAYERS: [(&str, &[&str]); 6] = [
    (
        "foundations",
        &["error", "exact", "quadrature", "solve", "deadline"],
    ),
    (
        "curves",
        &[
            "bernstein",
            "bezier",
            "bezpath",
            "lac",
            "bspline",
            "nurbs",
            "contour_points",
        ],
    ),
    (
        "measures",
        &["monotone", "lcg", "region", "outline", "space"],
    ),
    (
        "constructions",
        &[
            "approx",
            "approx_table",
            "pseudo_segment",
            "pseudo_table",
            "pseudo_spline",
            "lac_spline",
            "lac_fit",
            "sketch",
            "harmonize",
        ],
    ),
    ("interface", &["curve"]),
    ("support", &["samples"]),
];

#[test]
fn modules_use_only_their_layer_and_below() {
    let g = graph();
    // Every module has a layer, also one that uses nothing and that nothing uses.
    let unlayered: Vec<&String> = g
        .keys()
        .filter(|m| !LAYERS.iter().any(|(_, ms)| ms.contains(&m.as_str())))
        .collect();
    assert!(
        unlayered.is_empty(),
        "modules in no layer of docs/architecture.md: {unlayered:?}"
    );
    let layer = |m: &str| {
        LAYERS
            .iter()
            .position(|(_, ms)| ms.contains(&m))
            .unwrap_or_else(|| panic!("module {m} is in no layer of docs/architecture.md"))
    };
    let mut wrong = Vec::new();
    for (m, uses) in &g {
        for u in uses {
            if layer(u) > layer(m) {
                wrong.push(format!(
                    "{m} ({}) uses {u} ({})",
                    LAYERS[layer(m)].0,
                    LAYERS[layer(u)].0
                ));
            }
        }
    }
    assert!(wrong.is_empty(), "upward uses: {wrong:#?}");
}
