//! The house's rules, checked on the sources (issue 49): the sinks are peers and the sprite
//! tree links no encoder and no loader; no crate dev-depends on a crate that depends on it;
//! no module of a library crate imports, through others, a module that imports it; no
//! non-test function is longer than 150 lines.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::process::Command;

/// The library crates whose modules must not import each other in a circle.
const LIBRARIES: [&str; 7] = [
    "obj-quads",
    "face-sort",
    "aspect-bake",
    "sprite-compose",
    "vector-sink",
    "raster-sink",
    "xtask",
];

/// The longest non-test function allowed, in lines.
const LONGEST_FUNCTION: usize = 150;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// `cargo metadata` of the workspace's own packages: per package, its dependencies by kind
/// (`"normal"`, `"dev"`, `"build"`) with whether each is optional.
fn packages() -> BTreeMap<String, Vec<(String, String, bool)>> {
    let out = Command::new(env!("CARGO"))
        .args([
            "metadata",
            "--no-deps",
            "--format-version",
            "1",
            "--offline",
        ])
        .current_dir(root())
        .output()
        .expect("cargo metadata runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("metadata JSON");
    let mut packages = BTreeMap::new();
    for p in json["packages"].as_array().expect("packages") {
        let deps = (p["dependencies"].as_array().expect("dependencies").iter())
            .map(|d| {
                (
                    d["name"].as_str().unwrap_or_default().to_owned(),
                    d["kind"].as_str().unwrap_or("normal").to_owned(),
                    d["optional"].as_bool().unwrap_or(false),
                )
            })
            .collect();
        packages.insert(p["name"].as_str().expect("name").to_owned(), deps);
    }
    packages
}

/// Every workspace package that `name` depends on, directly or not, through normal and
/// build dependencies (optional ones included).
fn depends_on(
    packages: &BTreeMap<String, Vec<(String, String, bool)>>,
    name: &str,
) -> BTreeSet<String> {
    let mut seen = BTreeSet::new();
    let mut stack = vec![name.to_owned()];
    while let Some(p) = stack.pop() {
        for (dep, kind, _) in packages.get(&p).into_iter().flatten() {
            if kind != "dev" && packages.contains_key(dep) && seen.insert(dep.clone()) {
                stack.push(dep.clone());
            }
        }
    }
    seen
}

#[test]
fn the_sinks_are_peers_and_no_dev_dependency_comes_back() {
    let packages = packages();
    // The sprite tree links no encoder and no loader by default.
    let tree = &packages["sprite-compose"];
    for encoder in [
        "pdf-writer",
        "png",
        "miniz_oxide",
        "base64",
        "obj-quads",
        "i_overlay",
    ] {
        assert!(
            !tree
                .iter()
                .any(|(d, kind, optional)| d == encoder && kind == "normal" && !optional),
            "sprite-compose depends on {encoder}"
        );
    }
    // The sinks stand on it, beside each other, in every kind of dependency.
    for (a, b) in [
        ("raster-sink", "vector-sink"),
        ("vector-sink", "raster-sink"),
    ] {
        assert!(depends_on(&packages, a).contains("sprite-compose"), "{a}");
        assert!(
            !packages[a].iter().any(|(d, ..)| d == b),
            "{a} depends on {b}"
        );
        assert!(!depends_on(&packages, a).contains(b), "{a} depends on {b}");
    }
    // No crate dev-depends on a crate that depends on it.
    let mut cycles = Vec::new();
    for (name, deps) in &packages {
        for (dep, kind, _) in deps {
            if kind == "dev" && dep != name && depends_on(&packages, dep).contains(name) {
                cycles.push(format!(
                    "{name} dev-depends on {dep}, which depends on {name}"
                ));
            }
        }
    }
    assert!(cycles.is_empty(), "{cycles:#?}");
}

/// The `.rs` files under `dir`.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        let path = entry.path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// A source without its unit tests (`#[cfg(test)] mod tests` to the end of the file, where
/// the workspace keeps them).
fn without_tests(source: &str) -> &str {
    source
        .find("#[cfg(test)]\nmod tests")
        .map_or(source, |i| &source[..i])
}

/// The module path of a file under `src` (`""` for the crate root).
fn module_of(src: &Path, file: &Path) -> String {
    let relative = file
        .strip_prefix(src)
        .expect("under src")
        .with_extension("");
    let mut parts: Vec<String> = relative
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    if parts
        .last()
        .is_some_and(|p| p == "mod" || p == "lib" || p == "main")
    {
        parts.pop();
    }
    parts.join("::")
}

/// The modules `source` (module `module`, among `modules`) names through `crate::…` and
/// `super::…` paths, imports and doc links alike.
fn imports(
    module: &str,
    is_dir: bool,
    source: &str,
    modules: &BTreeSet<String>,
) -> BTreeSet<String> {
    let mut found = BTreeSet::new();
    let longest = |segments: &[&str]| -> Option<String> {
        (1..=segments.len())
            .rev()
            .map(|k| segments[..k].join("::"))
            .find(|m| modules.contains(m))
    };
    let parent: Vec<&str> = {
        let mut p: Vec<&str> = module.split("::").filter(|s| !s.is_empty()).collect();
        if !is_dir {
            p.pop();
        }
        p
    };
    for (prefix, base) in [("crate::", Vec::new()), ("super::", parent)] {
        for (i, _) in source.match_indices(prefix) {
            let before = source[..i].chars().next_back();
            if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
                continue;
            }
            let rest = &source[i + prefix.len()..];
            let items: Vec<&str> = if let Some(group) = rest.strip_prefix('{') {
                let end = group.find('}').unwrap_or(group.len());
                group[..end].split(',').map(str::trim).collect()
            } else {
                let end = rest
                    .find(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':'))
                    .unwrap_or(rest.len());
                vec![&rest[..end]]
            };
            for item in items {
                let mut segments = base.clone();
                segments.extend(item.split("::").filter(|s| !s.is_empty()));
                let named = longest(&segments).unwrap_or_else(|| base.join("::"));
                if named != module && !named.is_empty() {
                    found.insert(named);
                }
            }
        }
    }
    found
}

/// The strongly connected components of more than one module (Tarjan).
fn circles(graph: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    struct State<'a> {
        graph: &'a BTreeMap<String, BTreeSet<String>>,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        on: BTreeSet<&'a str>,
        out: Vec<Vec<String>>,
    }
    fn visit<'a>(s: &mut State<'a>, v: &'a str) {
        let n = s.index.len();
        s.index.insert(v, n);
        s.low.insert(v, n);
        s.stack.push(v);
        s.on.insert(v);
        for w in s.graph.get(v).into_iter().flatten() {
            let Some((w, _)) = s.graph.get_key_value(w) else {
                continue;
            };
            if !s.index.contains_key(w.as_str()) {
                visit(s, w);
                let low = s.low[w.as_str()].min(s.low[v]);
                s.low.insert(v, low);
            } else if s.on.contains(w.as_str()) {
                let low = s.index[w.as_str()].min(s.low[v]);
                s.low.insert(v, low);
            }
        }
        if s.low[v] == s.index[v] {
            let mut component = Vec::new();
            while let Some(w) = s.stack.pop() {
                s.on.remove(w);
                component.push(w.to_owned());
                if w == v {
                    break;
                }
            }
            if component.len() > 1 {
                s.out.push(component);
            }
        }
    }
    let mut state = State {
        graph,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on: BTreeSet::new(),
        out: Vec::new(),
    };
    for v in graph.keys() {
        if !state.index.contains_key(v.as_str()) {
            visit(&mut state, v);
        }
    }
    state.out
}

#[test]
fn no_module_circles_in_the_library_crates() {
    let mut found = Vec::new();
    for krate in LIBRARIES {
        let src = root().join(krate).join("src");
        let mut files = Vec::new();
        rust_files(&src, &mut files);
        let modules: BTreeSet<String> = files.iter().map(|f| module_of(&src, f)).collect();
        let mut graph = BTreeMap::new();
        for file in &files {
            let source = std::fs::read_to_string(file).expect("readable source");
            let module = module_of(&src, file);
            let is_dir = file
                .file_stem()
                .is_some_and(|s| s == "mod" || s == "lib" || s == "main");
            let edges = imports(&module, is_dir, without_tests(&source), &modules);
            graph.insert(module, edges);
        }
        for circle in circles(&graph) {
            found.push(format!("{krate}: {circle:?}"));
        }
    }
    assert!(
        found.is_empty(),
        "modules importing each other in a circle: {found:#?}"
    );
}

/// The functions of `source` longer than `limit` lines: `(name, first line, lines)`, from
/// each `fn` line to the closing brace at its indentation.
fn long_functions(source: &str, limit: usize) -> Vec<(String, usize, usize)> {
    let lines: Vec<&str> = without_tests(source).lines().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < lines.len() {
        let line = lines[i];
        let trimmed = line.trim_start();
        let indent = &line[..line.len() - trimmed.len()];
        let signature = [
            "fn ",
            "pub fn ",
            "pub(crate) fn ",
            "pub(super) fn ",
            "const fn ",
            "pub const fn ",
        ]
        .iter()
        .find_map(|p| trimmed.strip_prefix(p));
        let Some(rest) = signature else {
            i += 1;
            continue;
        };
        let name: String = rest
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        let mut j = i;
        while j < lines.len()
            && !lines[j].trim_end().ends_with('{')
            && !lines[j].trim_end().ends_with(';')
        {
            j += 1;
        }
        if j >= lines.len() || lines[j].trim_end().ends_with(';') {
            i = j + 1;
            continue;
        }
        let close = format!("{indent}}}");
        let end = (j + 1..lines.len())
            .find(|&k| lines[k].trim_end() == close)
            .unwrap_or(j);
        let length = end - i + 1;
        if length > limit {
            out.push((name, i + 1, length));
        }
        i = end + 1;
    }
    out
}

#[test]
fn no_function_is_longer_than_150_lines() {
    let mut found = Vec::new();
    for krate in [
        "obj-quads",
        "face-sort",
        "aspect-bake",
        "sprite-compose",
        "vector-sink",
        "raster-sink",
        "xtask",
        "python",
        "wasm",
    ] {
        let mut files = Vec::new();
        rust_files(&root().join(krate).join("src"), &mut files);
        for file in files {
            let source = std::fs::read_to_string(&file).expect("readable source");
            for (name, line, length) in long_functions(&source, LONGEST_FUNCTION) {
                found.push(format!("{}:{line} {name}: {length} lines", file.display()));
            }
        }
    }
    assert!(found.is_empty(), "{found:#?}");
}

#[test]
fn the_checks_find_what_they_look_for() {
    // A circle of two modules, through an import and a doc link.
    let modules: BTreeSet<String> = ["a", "b"].map(str::to_owned).into();
    let mut graph = BTreeMap::new();
    graph.insert(
        "a".to_owned(),
        imports("a", false, "use crate::b::X;", &modules),
    );
    graph.insert(
        "b".to_owned(),
        imports("b", false, "/// [`Y`](crate::a::Y)", &modules),
    );
    assert_eq!(circles(&graph).len(), 1);
    graph.insert("b".to_owned(), BTreeSet::new());
    assert!(circles(&graph).is_empty());
    // A function of 152 lines, and one of 3.
    let long = format!(
        "fn long() {{\n{}}}\nfn short() {{\n    1;\n}}\n",
        "    x;\n".repeat(150)
    );
    let found = long_functions(&long, LONGEST_FUNCTION);
    assert_eq!(found, vec![("long".to_owned(), 1, 152)]);
}
