//! The layering of `docs/ARCHITECTURE.md`, checked on the source: every module of the library
//! imports only the modules this table allows (the layers below it), the three algorithms
//! never import each other, the library neither names nor depends on the command line's
//! crates (argument parser, progress bars, Ctrl-C handler, `anyhow`), and the command line
//! reaches the library only through the method API and the scene, report, image, validation
//! and output-file modules.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Each library module and the modules it may import, layer by layer from the bottom.
const ALLOWED: &[(&str, &[&str])] = &[
    // Foundations.
    ("color", &[]),
    ("lanes", &[]),
    ("choice", &[]),
    ("atomic_file", &[]),
    // The sun's position and the CIE skies: pure functions over `glam`.
    ("sky", &[]),
    ("geometry", &["lanes"]),
    ("sampling", &["color", "geometry", "lanes"]),
    // The scene model and acceleration structures.
    ("scene", &["color", "geometry", "sky"]),
    ("accel", &["choice", "geometry"]),
    // The scene compiled for ray queries.
    (
        "world",
        &[
            "accel", "choice", "color", "geometry", "lanes", "sampling", "scene", "sky",
        ],
    ),
    // What the algorithms fill.
    (
        "measure",
        &["choice", "color", "geometry", "scene", "world"],
    ),
    // Progress, cancellation and the solutions between rounds, handed to whoever listens.
    ("progress", &["measure"]),
    // The algorithms, side by side.
    ("trace", ALGORITHM_BASE),
    ("light_model", ALGORITHM_BASE),
    ("radiosity", ALGORITHM_BASE),
    // Two algorithms together: images and reported surfaces.
    (
        "final_gather",
        &[
            "color",
            "geometry",
            "measure",
            "progress",
            "radiosity",
            "sampling",
            "trace",
            "world",
        ],
    ),
    // The method API: every method named with its settings and run by one call.
    (
        "method",
        &[
            "accel",
            "choice",
            "color",
            "final_gather",
            "geometry",
            "light_model",
            "measure",
            "progress",
            "radiosity",
            "sampling",
            "scene",
            "trace",
            "world",
        ],
    ),
    // Files made from what was measured.
    ("image", &["atomic_file", "choice", "color", "measure"]),
    (
        "report",
        &["atomic_file", "color", "image", "measure", "scene"],
    ),
    // The validation suite, over the method API.
    ("validate", &["color", "method", "scene"]),
];

/// The library modules the front ends (the command line, `cli/src`, and the Python
/// package, `python/src`) may import: the method API and the scene, report, image,
/// validation and output-file modules.
const FRONT_END_MODULES: &[&str] = &[
    "atomic_file",
    "image",
    "method",
    "report",
    "scene",
    "validate",
];

/// What every algorithm may import: everything below the algorithms.
const ALGORITHM_BASE: &[&str] = &[
    "accel", "choice", "color", "geometry", "lanes", "measure", "progress", "sampling", "scene",
    "world",
];

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The code of a file without its comments (doc links may name any module).
fn code(path: &Path) -> String {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .map(|line| match line.find("//") {
            Some(i) => &line[..i],
            None => line,
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// The top-level modules a piece of code names through `crate::` paths, grouped imports
/// (`crate::{a::X, b}`) included.
fn crate_modules(code: &str) -> BTreeSet<String> {
    let mut found = BTreeSet::new();
    let mut rest = code;
    while let Some(i) = rest.find("crate::") {
        rest = &rest[i + "crate::".len()..];
        if let Some(group) = rest.strip_prefix('{') {
            let mut depth = 0;
            let mut start = 0;
            for (k, ch) in group.char_indices() {
                match ch {
                    '{' => depth += 1,
                    '}' if depth == 0 => {
                        found.extend(first_segment(&group[start..k]));
                        break;
                    }
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        found.extend(first_segment(&group[start..k]));
                        start = k + 1;
                    }
                    _ => {}
                }
            }
        } else {
            found.extend(first_segment(rest));
        }
    }
    found
}

fn first_segment(path: &str) -> Option<String> {
    let name: String = path
        .trim_start()
        .chars()
        .take_while(|c| c.is_alphanumeric() || *c == '_')
        .collect();
    (!name.is_empty() && name != "self").then_some(name)
}

/// The top-level module a file of `src/` belongs to (`None` for the crate roots).
fn module_of(src: &Path, file: &Path) -> Option<String> {
    let relative = file.strip_prefix(src).unwrap();
    let first = relative
        .components()
        .next()?
        .as_os_str()
        .to_str()?
        .to_string();
    let name = first.trim_end_matches(".rs").to_string();
    (name != "lib" && name != "main").then_some(name)
}

#[test]
fn modules_import_only_the_layers_below_them() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let allowed: BTreeMap<&str, &[&str]> = ALLOWED.iter().copied().collect();
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut violations = Vec::new();
    let mut seen = BTreeSet::new();
    for file in &files {
        let Some(module) = module_of(&src, file) else {
            continue;
        };
        seen.insert(module.clone());
        let Some(may) = allowed.get(module.as_str()) else {
            violations.push(format!(
                "{}: module '{module}' is not in the table",
                file.display()
            ));
            continue;
        };
        for used in crate_modules(&code(file)) {
            if used != module && !may.contains(&used.as_str()) {
                violations.push(format!("{}: {module} imports {used}", file.display()));
            }
        }
    }
    let listed: BTreeSet<String> = allowed.keys().map(|k| k.to_string()).collect();
    assert_eq!(
        seen, listed,
        "the table lists exactly the library's modules"
    );
    assert!(violations.is_empty(), "{}", violations.join("\n"));
}

/// Crates only the command line (`cli/`, the `strahl-cli` crate) may use.
const FRONT_END_CRATES: &[&str] = &[
    "clap",
    "anyhow",
    "indicatif",
    "ctrlc",
    "tiny_http",
    "strahl_cli",
];

#[test]
fn the_library_knows_no_command_line() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let src = root.join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    for file in &files {
        let code = code(file);
        for name in FRONT_END_CRATES {
            assert!(
                !code.contains(&format!("{name}::")) && !code.contains(&format!("use {name}")),
                "{} names {name}: only the command line (cli/) may",
                file.display()
            );
        }
    }
    // Nor does it depend on them (`cargo tree -p strahl -e normal` shows none).
    let manifest = std::fs::read_to_string(root.join("Cargo.toml")).unwrap();
    let dependencies = manifest
        .split("[dependencies]")
        .nth(1)
        .and_then(|rest| rest.split("\n[").next())
        .unwrap();
    for name in FRONT_END_CRATES {
        assert!(
            !dependencies
                .lines()
                .any(|line| line.trim_start().starts_with(&format!("{name} "))),
            "the library depends on {name}"
        );
    }
}

/// The library modules a piece of the command line names through `strahl::` paths.
fn library_modules(code: &str) -> BTreeSet<String> {
    crate_modules(&code.replace("strahl::", "crate::"))
}

#[test]
fn the_command_line_and_the_python_package_use_only_the_method_api_and_the_file_modules() {
    let mut files = Vec::new();
    for front_end in ["cli/src", "python/src"] {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join(front_end);
        let before = files.len();
        rust_files(&dir, &mut files);
        assert!(files.len() > before, "no sources in {}", dir.display());
    }
    let mut violations = Vec::new();
    for file in &files {
        for used in library_modules(&code(file)) {
            if !FRONT_END_MODULES.contains(&used.as_str()) {
                violations.push(format!("{} imports strahl::{used}", file.display()));
            }
        }
    }
    assert!(violations.is_empty(), "{}", violations.join("\n"));
}

#[test]
fn the_import_reader_sees_grouped_and_nested_paths() {
    let code = "use crate::{a::X, b::{c, d}, e};\nlet v = crate::f::g();\n$crate::h::i!();";
    let found: Vec<String> = crate_modules(code).into_iter().collect();
    assert_eq!(found, ["a", "b", "e", "f", "h"]);
}

/// The module path of a file of `src/` (`radiosity::solve::matrix`; `mod.rs` names its
/// folder; `None` for the crate root).
fn module_path(src: &Path, file: &Path) -> Option<Vec<String>> {
    let relative = file.strip_prefix(src).ok()?.with_extension("");
    let mut parts: Vec<String> = relative
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    if parts.last().is_some_and(|p| p == "mod") {
        parts.pop();
    }
    (parts != ["lib"]).then_some(parts)
}

/// The paths a piece of code names from `crate::` or `super::`, grouped imports expanded
/// (`super::{a::X, b}` gives `super::a::X` and `super::b`), as segments.
fn named_paths(code: &str) -> Vec<Vec<String>> {
    let mut paths = Vec::new();
    let is_word = |c: char| c.is_alphanumeric() || c == '_';
    let mut rest = code;
    while let Some(i) = rest.find(['c', 's']) {
        let preceded = i > 0 && rest[..i].chars().next_back().is_some_and(is_word);
        let tail = &rest[i..];
        let start = if preceded {
            None
        } else if tail.starts_with("crate::") || tail.starts_with("super::") {
            Some(tail)
        } else {
            None
        };
        rest = &rest[i + 1..];
        let Some(tail) = start else {
            continue;
        };
        let mut prefix = Vec::new();
        let mut at = tail;
        loop {
            let word: String = at.chars().take_while(|&c| is_word(c)).collect();
            if word.is_empty() {
                break;
            }
            prefix.push(word.clone());
            at = &at[word.len()..];
            if let Some(next) = at.strip_prefix("::") {
                at = next;
                if let Some(group) = at.strip_prefix('{') {
                    let end = group.find('}').unwrap_or(group.len());
                    for item in group[..end].split(',') {
                        let mut path = prefix.clone();
                        path.extend(
                            item.trim()
                                .split("::")
                                .map(|s| s.trim().to_string())
                                .filter(|s| !s.is_empty() && s != "{"),
                        );
                        paths.push(path);
                    }
                    prefix.clear();
                    break;
                }
            } else {
                break;
            }
        }
        if !prefix.is_empty() {
            paths.push(prefix);
        }
    }
    paths
}

#[test]
fn the_files_of_the_library_import_one_another_without_cycles() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let modules: BTreeMap<String, (PathBuf, Vec<String>)> = files
        .iter()
        .filter_map(|f| {
            let path = module_path(&src, f)?;
            Some((path.join("::"), (f.clone(), path)))
        })
        .collect();
    let without_tests = |f: &Path| {
        let c = code(f);
        match c.find("#[cfg(test)]") {
            Some(i) => c[..i].to_string(),
            None => c,
        }
    };
    // Names a folder's `mod.rs` re-exports from one of its files: (folder, name) → file.
    let mut reexported: BTreeMap<(String, String), String> = BTreeMap::new();
    for (name, (file, _)) in &modules {
        if !file.ends_with("mod.rs") {
            continue;
        }
        for line in without_tests(file).split(';') {
            let Some(used) = line.trim().strip_prefix("pub use ") else {
                continue;
            };
            let child = used.split("::").next().unwrap_or("").trim();
            let module = format!("{name}::{child}");
            if !modules.contains_key(&module) {
                continue;
            }
            let items = used
                .split_once('{')
                .map_or(used.rsplit("::").next(), |(_, g)| {
                    Some(g.trim_end_matches('}'))
                });
            for item in items.unwrap_or("").split(',') {
                let item = item.trim().trim_end_matches('}').trim();
                if !item.is_empty() {
                    reexported.insert((name.clone(), item.to_string()), module.clone());
                }
            }
        }
    }
    let resolve = |path: &[String]| -> Option<String> {
        (1..=path.len()).rev().find_map(|k| {
            let module = path[..k].join("::");
            modules.contains_key(&module).then(|| {
                path.get(k)
                    .and_then(|n| reexported.get(&(module.clone(), n.clone())))
                    .cloned()
                    .unwrap_or(module)
            })
        })
    };
    let mut edges: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (name, (file, parts)) in &modules {
        for named in named_paths(&without_tests(file)) {
            // `super` is the module's parent (a file's folder, a folder's parent).
            let absolute: Vec<String> = if named[0] == "crate" {
                named[1..].to_vec()
            } else {
                let mut base = parts.clone();
                let ups = named.iter().take_while(|s| *s == "super").count();
                base.truncate(base.len().saturating_sub(ups));
                base.extend(named[ups..].iter().cloned());
                base
            };
            if let Some(target) = resolve(&absolute)
                && &target != name
                && !name.starts_with(&format!("{target}::"))
            {
                edges.entry(name.clone()).or_default().insert(target);
            }
        }
    }
    // Depth-first search for a path back to where it started.
    fn cycle_from(
        start: &str,
        at: &str,
        edges: &BTreeMap<String, BTreeSet<String>>,
        path: &mut Vec<String>,
        seen: &mut BTreeSet<String>,
    ) -> Option<Vec<String>> {
        for next in edges.get(at).into_iter().flatten() {
            if next == start {
                let mut cycle = path.clone();
                cycle.push(start.to_string());
                return Some(cycle);
            }
            if seen.insert(next.clone()) {
                path.push(next.clone());
                if let Some(c) = cycle_from(start, next, edges, path, seen) {
                    return Some(c);
                }
                path.pop();
            }
        }
        None
    }
    let cycles: Vec<String> = edges
        .keys()
        .filter_map(|m| {
            cycle_from(m, m, &edges, &mut vec![m.clone()], &mut BTreeSet::new())
                .map(|c| c.join(" → "))
        })
        .collect();
    assert!(cycles.is_empty(), "import cycles:\n{}", cycles.join("\n"));
    // The reader sees the imports it is meant to.
    assert!(edges["radiosity::contact"].contains("radiosity::clip"));
    assert!(edges["radiosity::solve::hierarchical::solver"].contains("radiosity::solve::solution"));
}
