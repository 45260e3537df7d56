//! The house rules of issue 41, measured on the source of both crates (`src/` and the solvers'
//! `crates/physics/src/`, read as the `physics` module it is re-exported as): no file over 800
//! lines, no function over 150 lines outside tests, no import circle between files, and no
//! `utoipa` in physics. The measurement is plain text (comments and test modules left out),
//! so it needs no compiler plugin; `cargo test --test it house_plan -- --nocapture` prints
//! what it found.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

const MAX_FILE_LINES: usize = 800;
const MAX_FN_LINES: usize = 150;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).to_path_buf()
}

/// The physics crate's sources, mounted at `crate::physics` of the service crate.
const PHYSICS_SRC: &str = "crates/physics/src";

/// Every `.rs` file under `src/` and the physics crate's `src/`, as paths relative to the repository.
fn sources() -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![root().join("src"), root().join(PHYSICS_SRC)];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let p = entry.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|e| e == "rs") {
                out.push(p.strip_prefix(root()).unwrap().to_path_buf());
            }
        }
    }
    out.sort();
    out
}

/// The file's lines with string literals, char literals and comments blanked (braces inside them
/// do not count), and the `#[cfg(test)]` items removed (their lines kept empty so that line
/// numbers hold).
fn code_lines(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut in_block_comment = 0usize;
    let mut in_string = false;
    for line in text.lines() {
        let mut s = String::with_capacity(line.len());
        let chars: Vec<char> = line.chars().collect();
        let mut i = 0;
        while i < chars.len() {
            let c = chars[i];
            let next = chars.get(i + 1).copied();
            if in_block_comment > 0 {
                if c == '*' && next == Some('/') {
                    in_block_comment -= 1;
                    i += 2;
                    continue;
                }
                if c == '/' && next == Some('*') {
                    in_block_comment += 1;
                    i += 2;
                    continue;
                }
                i += 1;
                continue;
            }
            if in_string {
                if c == '\\' {
                    i += 2;
                    continue;
                }
                if c == '"' {
                    in_string = false;
                    s.push('"');
                }
                i += 1;
                continue;
            }
            match (c, next) {
                ('/', Some('/')) => break,
                ('/', Some('*')) => {
                    in_block_comment += 1;
                    i += 2;
                }
                ('"', _) => {
                    // Raw strings r"…" / r#"…"# are rare here; treated as plain strings.
                    in_string = true;
                    s.push('"');
                    i += 1;
                }
                ('\'', _) => {
                    // A char literal ('{', '\'', '\u{..}') or a lifetime ('a).
                    let rest: String = chars[i..].iter().take(12).collect();
                    if let Some(end) = char_literal_len(&rest) {
                        s.push_str("' '");
                        i += end;
                    } else {
                        s.push(c);
                        i += 1;
                    }
                }
                _ => {
                    s.push(c);
                    i += 1;
                }
            }
        }
        out.push(s);
    }
    strip_test_items(out)
}

/// Length of a char literal at the start of `s`, if it is one.
fn char_literal_len(s: &str) -> Option<usize> {
    let c: Vec<char> = s.chars().collect();
    if c.len() >= 3 && c[1] != '\\' && c[2] == '\'' {
        return Some(3);
    }
    if c.len() >= 4 && c[1] == '\\' {
        let close = c.iter().skip(2).position(|&x| x == '\'')?;
        return Some(close + 3);
    }
    None
}

/// Blank the items under `#[cfg(test)]` (a test module or function).
fn strip_test_items(mut lines: Vec<String>) -> Vec<String> {
    let mut i = 0;
    while i < lines.len() {
        if lines[i].trim() == "#[cfg(test)]" {
            // The item starts here; blank until its braces close.
            let mut depth = 0i64;
            let mut opened = false;
            let mut j = i;
            while j < lines.len() {
                for ch in lines[j].chars() {
                    if ch == '{' {
                        depth += 1;
                        opened = true;
                    } else if ch == '}' {
                        depth -= 1;
                    }
                }
                let done = (opened && depth <= 0) || (!opened && lines[j].trim_end().ends_with(';'));
                lines[j].clear();
                j += 1;
                if done {
                    break;
                }
            }
            i = j;
        } else {
            i += 1;
        }
    }
    lines
}

/// Functions (name, first line, length in lines) of one file, nested ones included.
fn functions(lines: &[String]) -> Vec<(String, usize, usize)> {
    let mut out = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let t = line.trim_start();
        let Some(pos) = t.find("fn ") else { continue };
        let head = &t[..pos];
        let is_fn = head.split_whitespace().all(|w| {
            matches!(w, "pub" | "async" | "unsafe" | "const" | "extern" | "default") || w.starts_with("pub(") || w.starts_with("extern")
        });
        if !is_fn {
            continue;
        }
        let name: String = t[pos + 3..].chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
        if name.is_empty() {
            continue;
        }
        // The body: from the first `{` after the signature to its matching `}`; a `;` first,
        // outside brackets (not the one of `[f64; 2]`), means a declaration without a body
        // (trait method).
        let mut depth = 0i64;
        let mut brackets = 0i64;
        let mut opened = false;
        let mut end = None;
        'scan: for (j, l) in lines.iter().enumerate().skip(i) {
            for ch in l.chars() {
                match ch {
                    '(' | '[' if !opened => brackets += 1,
                    ')' | ']' if !opened => brackets -= 1,
                    '{' => {
                        depth += 1;
                        opened = true;
                    }
                    '}' => {
                        depth -= 1;
                        if opened && depth == 0 {
                            end = Some(j);
                            break 'scan;
                        }
                    }
                    ';' if !opened && brackets == 0 => break 'scan,
                    _ => {}
                }
            }
        }
        if let Some(e) = end {
            out.push((name, i + 1, e - i + 1));
        }
    }
    out
}

/// The module file of a `crate::a::b` path prefix: `src/a/b.rs` or `src/a/b/mod.rs`
/// (`crate::physics::a` is the physics crate's `a`).
fn module_file(segments: &[&str]) -> Option<PathBuf> {
    let (dir, segments) = match segments.split_first() {
        Some((&"physics", rest)) => (PHYSICS_SRC, rest),
        _ => ("src", segments),
    };
    if segments.is_empty() {
        return Some(PathBuf::from(format!("{dir}/lib.rs")));
    }
    let base = segments.join("/");
    for candidate in [format!("{dir}/{base}.rs"), format!("{dir}/{base}/mod.rs")] {
        if root().join(&candidate).exists() {
            return Some(PathBuf::from(candidate));
        }
    }
    None
}

/// The module path of a source file (`crates/physics/src/ehl/twod/mod.rs` → `physics ehl twod`).
fn module_of(file: &Path) -> Vec<String> {
    let mut parts = crate_prefix(file);
    let rel = file.strip_prefix(PHYSICS_SRC).or_else(|_| file.strip_prefix("src")).unwrap();
    parts.extend(rel.iter().map(|p| p.to_string_lossy().to_string()));
    let last = parts.pop().unwrap();
    if last != "mod.rs" && last != "lib.rs" && last != "main.rs" {
        parts.push(last.trim_end_matches(".rs").to_string());
    }
    parts
}

/// What `crate::` means in a file: the service crate's root, or `physics` for the solvers' crate.
fn crate_prefix(file: &Path) -> Vec<String> {
    if file.starts_with(PHYSICS_SRC) { vec!["physics".to_string()] } else { Vec::new() }
}

/// Whether a file is a crate root (its `crate::` items are the crate's, not a module's).
fn is_crate_root(f: &Path) -> bool {
    f == Path::new("src/lib.rs") || f == Path::new(PHYSICS_SRC).join("lib.rs")
}

/// Files a file imports from: `use crate::…`, `use super::…` and `crate::…::` paths in code, each
/// resolved to the deepest module file the path names. Re-exports (`pub use`) are not edges: they
/// publish a child's item from its parent.
fn imports(file: &Path, lines: &[String]) -> BTreeSet<PathBuf> {
    let module = module_of(file);
    let mut out = BTreeSet::new();
    let text = lines.join("\n");
    let mut statements: Vec<String> = Vec::new();
    // `use` statements (possibly spanning lines), without re-exports.
    let mut rest = text.as_str();
    while let Some(pos) = rest.find("use ") {
        let before = &rest[..pos];
        let is_stmt = before.ends_with('\n') || before.ends_with(' ') || before.is_empty() || before.ends_with('{') || before.ends_with(';');
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        let prefix = before[line_start..].trim();
        let end = rest[pos..].find(';').map_or(rest.len(), |e| pos + e);
        if is_stmt && !prefix.starts_with("pub") && (prefix.is_empty() || prefix.ends_with('{') || prefix.ends_with('}')) {
            statements.push(rest[pos + 4..end].to_string());
        }
        rest = &rest[end.min(rest.len())..];
        if rest.is_empty() {
            break;
        }
        rest = &rest[1.min(rest.len())..];
    }
    // Inline `crate::a::b::c` and `super::a::b` paths in code.
    for start in ["crate::", "super::"] {
        for (i, _) in text.match_indices(start) {
            let prev = text[..i].chars().next_back();
            if prev.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':') {
                continue;
            }
            let path: String = text[i..].chars().take_while(|c| c.is_alphanumeric() || *c == '_' || *c == ':').collect();
            statements.push(path);
        }
    }
    // Child modules named in code (`mod docs;` … `docs::file()`).
    for line in lines {
        let t = line.trim();
        let decl = t.strip_prefix("pub ").unwrap_or(t).strip_prefix("pub(crate) ").unwrap_or(t.strip_prefix("pub ").unwrap_or(t));
        if let Some(name) = decl.strip_prefix("mod ").and_then(|r| r.strip_suffix(';')) {
            if text.contains(&format!("{name}::")) {
                statements.push(format!("self::{name}::x"));
            }
        }
    }
    for st in statements {
        for path in expand(&st) {
            let segs: Vec<&str> = path.split("::").filter(|s| !s.is_empty()).collect();
            let absolute: Vec<String> = match segs.first() {
                Some(&"crate") => crate_prefix(file).into_iter().chain(segs[1..].iter().map(|s| s.to_string())).collect(),
                Some(&"super") => {
                    let mut m = module.clone();
                    let mut k = 0;
                    while segs.get(k) == Some(&"super") {
                        m.pop();
                        k += 1;
                    }
                    m.extend(segs[k..].iter().map(|s| s.to_string()));
                    m
                }
                Some(&"self") => {
                    let mut m = module.clone();
                    m.extend(segs[1..].iter().map(|s| s.to_string()));
                    m
                }
                _ => continue,
            };
            // The deepest prefix that is a module file.
            let refs: Vec<&str> = absolute.iter().map(String::as_str).collect();
            for n in (0..=refs.len()).rev() {
                if let Some(f) = module_file(&refs[..n]) {
                    if f != file && !is_crate_root(&f) {
                        out.insert(f);
                    }
                    break;
                }
            }
        }
    }
    out
}

/// `a::{b, c::{d, e}}` → `a::b`, `a::c::d`, `a::c::e`.
fn expand(st: &str) -> Vec<String> {
    let st: String = st.split_whitespace().collect::<Vec<_>>().join("");
    fn go(prefix: &str, s: &str, out: &mut Vec<String>) {
        if let Some(open) = s.find('{') {
            let head = &s[..open];
            let inner = &s[open + 1..s.rfind('}').unwrap_or(s.len())];
            // Split the inner list at top-level commas.
            let mut depth = 0;
            let mut start = 0;
            let bytes: Vec<char> = inner.chars().collect();
            let mut parts = Vec::new();
            for (i, &c) in bytes.iter().enumerate() {
                match c {
                    '{' => depth += 1,
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        parts.push(bytes[start..i].iter().collect::<String>());
                        start = i + 1;
                    }
                    _ => {}
                }
            }
            parts.push(bytes[start..].iter().collect::<String>());
            for p in parts {
                if !p.is_empty() {
                    go(&format!("{prefix}{head}"), &p, out);
                }
            }
        } else {
            let s = s.split(" as ").next().unwrap_or(s).split("as").next().unwrap_or(s);
            out.push(format!("{prefix}{s}"));
        }
    }
    let mut out = Vec::new();
    go("", &st, &mut out);
    out
}

/// Strongly connected components of more than one file (Tarjan).
fn circles(graph: &BTreeMap<PathBuf, BTreeSet<PathBuf>>) -> Vec<Vec<PathBuf>> {
    struct T<'a> {
        g: &'a BTreeMap<PathBuf, BTreeSet<PathBuf>>,
        index: BTreeMap<&'a PathBuf, usize>,
        low: BTreeMap<&'a PathBuf, usize>,
        stack: Vec<&'a PathBuf>,
        on: BTreeSet<&'a PathBuf>,
        next: usize,
        out: Vec<Vec<PathBuf>>,
    }
    fn visit<'a>(t: &mut T<'a>, v: &'a PathBuf) {
        t.index.insert(v, t.next);
        t.low.insert(v, t.next);
        t.next += 1;
        t.stack.push(v);
        t.on.insert(v);
        if let Some(ws) = t.g.get(v) {
            for w in ws {
                let Some((w, _)) = t.g.get_key_value(w) else { continue };
                if !t.index.contains_key(w) {
                    visit(t, w);
                    let lw = t.low[w];
                    let lv = t.low[v];
                    t.low.insert(v, lv.min(lw));
                } else if t.on.contains(w) {
                    let iw = t.index[w];
                    let lv = t.low[v];
                    t.low.insert(v, lv.min(iw));
                }
            }
        }
        if t.low[v] == t.index[v] {
            let mut comp = Vec::new();
            while let Some(w) = t.stack.pop() {
                t.on.remove(w);
                comp.push(w.clone());
                if w == v {
                    break;
                }
            }
            if comp.len() > 1 {
                comp.sort();
                t.out.push(comp);
            }
        }
    }
    let mut t = T { g: graph, index: BTreeMap::new(), low: BTreeMap::new(), stack: Vec::new(), on: BTreeSet::new(), next: 0, out: Vec::new() };
    for v in graph.keys() {
        if !t.index.contains_key(v) {
            visit(&mut t, v);
        }
    }
    t.out
}

struct Survey {
    long_files: Vec<(PathBuf, usize)>,
    long_functions: Vec<(PathBuf, String, usize, usize)>,
    circles: Vec<Vec<PathBuf>>,
    utoipa_in_physics: Vec<PathBuf>,
}

fn survey() -> Survey {
    let mut s = Survey { long_files: Vec::new(), long_functions: Vec::new(), circles: Vec::new(), utoipa_in_physics: Vec::new() };
    let mut graph = BTreeMap::new();
    for file in sources() {
        let text = std::fs::read_to_string(root().join(&file)).unwrap();
        let n = text.lines().count();
        if n > MAX_FILE_LINES {
            s.long_files.push((file.clone(), n));
        }
        let lines = code_lines(&text);
        for (name, at, len) in functions(&lines) {
            if len > MAX_FN_LINES {
                s.long_functions.push((file.clone(), name, at, len));
            }
        }
        if file.starts_with(PHYSICS_SRC) && lines.iter().any(|l| l.contains("utoipa")) {
            s.utoipa_in_physics.push(file.clone());
        }
        graph.insert(file.clone(), imports(&file, &lines));
    }
    s.circles = house_circles(&graph);
    s
}

/// The module file a file belongs to as a child (`src/a/b.rs` → `src/a/mod.rs` or `src/a.rs`…):
/// the parent that declares it.
fn parent_of(file: &Path) -> Option<PathBuf> {
    let mut m = module_of(file);
    m.pop()?;
    let refs: Vec<&str> = m.iter().map(String::as_str).collect();
    module_file(&refs)
}

/// Circles of the house, counted as a reader of the layout sees them: between files (a module
/// file and the files it declares reach into each other by construction — it publishes and
/// dispatches to them, they use its shared types — so those pairs are one unit), and between
/// folders (a folder's files together against another folder's, a folder and its own sub-folder
/// again one unit).
fn house_circles(graph: &BTreeMap<PathBuf, BTreeSet<PathBuf>>) -> Vec<Vec<PathBuf>> {
    let family = |a: &Path, b: &Path| parent_of(a).as_deref() == Some(b) || parent_of(b).as_deref() == Some(a);
    let files: BTreeMap<PathBuf, BTreeSet<PathBuf>> = graph
        .iter()
        .map(|(a, bs)| (a.clone(), bs.iter().filter(|b| !family(a, b)).cloned().collect()))
        .collect();
    let folder = |f: &Path| f.parent().unwrap().to_path_buf();
    let related = |a: &Path, b: &Path| a.starts_with(b) && a.components().count() == b.components().count() + 1;
    let mut folders: BTreeMap<PathBuf, BTreeSet<PathBuf>> = BTreeMap::new();
    for (a, bs) in graph {
        let fa = folder(a);
        let entry = folders.entry(fa.clone()).or_default();
        for b in bs {
            let fb = folder(b);
            if fb != fa && !related(&fa, &fb) && !related(&fb, &fa) {
                entry.insert(fb);
            }
        }
    }
    let mut out = circles(&files);
    out.extend(circles(&folders));
    out
}

/// No file over 800 lines (`cargo test --test it house_plan -- --nocapture` prints the survey).
#[test]
fn no_file_is_over_800_lines() {
    let s = survey();
    assert!(s.long_files.is_empty(), "files over {MAX_FILE_LINES} lines: {:?}", s.long_files);
}

/// Functions still over the cap when the rule was written (issue 41), with their length then: each
/// may only shrink, and leaves this list when it is under the cap. No other function may exceed it.
const LONG_FUNCTIONS_LEFT: &[(&str, &str, usize)] = &[
];

/// No function over 150 lines outside test code, but for the ones listed above, which may only
/// shrink.
#[test]
fn no_function_is_over_150_lines() {
    let s = survey();
    let mut over = Vec::new();
    for (f, name, at, len) in &s.long_functions {
        let known = LONG_FUNCTIONS_LEFT.iter().find(|(kf, kn, _)| Path::new(kf) == f.as_path() && kn == name);
        match known {
            Some((_, _, was)) if len <= was => {}
            Some((_, _, was)) => over.push(format!("{}:{at} {name} grew from {was} to {len} lines", f.display())),
            None => over.push(format!("{}:{at} {name} ({len} lines)", f.display())),
        }
    }
    assert!(over.is_empty(), "functions over {MAX_FN_LINES} lines:\n{}", over.join("\n"));
    let stale: Vec<&str> = LONG_FUNCTIONS_LEFT
        .iter()
        .filter(|(kf, kn, _)| !s.long_functions.iter().any(|(f, n, _, _)| Path::new(kf) == f.as_path() && n == kn))
        .map(|(_, kn, _)| *kn)
        .collect();
    assert!(stale.is_empty(), "under the cap now, take them off LONG_FUNCTIONS_LEFT: {stale:?}");
}

/// No import circle between files (a module file and the files it declares are one unit) nor
/// between folders (a folder and its own sub-folder are one unit).
#[test]
fn no_import_circles() {
    let s = survey();
    assert!(s.circles.is_empty(), "import circles: {:?}", s.circles);
}

/// Physics carries no transport types: `utoipa` appears nowhere in the solvers' crate.
#[test]
fn no_utoipa_in_physics() {
    let s = survey();
    assert!(s.utoipa_in_physics.is_empty(), "utoipa in physics: {:?}", s.utoipa_in_physics);
}

/// Prints the measurements (`-- --nocapture`); the rules above enforce them.
#[test]
fn the_house_as_measured() {
    let s = survey();
    eprintln!("files over {MAX_FILE_LINES} lines: {:?}", s.long_files);
    for (f, name, at, len) in &s.long_functions {
        eprintln!("function over {MAX_FN_LINES} lines: {}:{at} {name} ({len})", f.display());
    }
    for c in &s.circles {
        eprintln!("import circle: {c:?}");
    }
    eprintln!("utoipa in physics: {:?}", s.utoipa_in_physics);
}

/// The measurement itself: a known circle and a known long function are found.
#[test]
fn the_survey_sees_circles_and_long_functions() {
    let mut g = BTreeMap::new();
    let (a, b, c) = (PathBuf::from("a"), PathBuf::from("b"), PathBuf::from("c"));
    g.insert(a.clone(), BTreeSet::from([b.clone()]));
    g.insert(b.clone(), BTreeSet::from([a.clone(), c.clone()]));
    g.insert(c.clone(), BTreeSet::new());
    assert_eq!(circles(&g), vec![vec![a, b]]);
    let src = "fn short() {\n    let s = \"}\";\n}\n#[cfg(test)]\nmod tests {\n    fn long() {\n    }\n}\npub(crate) fn two(x: u8) -> u8 {\n    let c = '{';\n    x\n}\n";
    let f = functions(&code_lines(src));
    assert_eq!(f, vec![("short".to_string(), 1, 3), ("two".to_string(), 9, 4)]);
    assert_eq!(expand("crate::a::{b, c::{d, e as f}}"), vec!["crate::a::b", "crate::a::c::d", "crate::a::c::e"]);
}
