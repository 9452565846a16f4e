//! The crate's layering, checked. `src/lib.rs` opens with its modules in
//! order, and a module may use only the modules named before it: so every
//! dependency runs one way and a reader can trust the list. This test reads
//! the list from that comment (the two cannot drift apart) and every `.rs`
//! file under `src/`, finds each module's paths into other modules —
//! `use crate::x`, `crate::x::…` in code, `use crate::{a, b}` groups,
//! `super::` paths that leave the module, and the crate root's re-exports
//! (`crate::Surface` is `surface`'s) — and fails on a path to a module named
//! later, or on a module the list leaves out, naming the file and line.
//! Inside a module, its sub-modules must not use each other in a cycle
//! either. And no module adds methods to another module's type (an `impl
//! Surface` block outside `surface`): such a block needs no path to the
//! module above, so it would hide who depends on whom, and scatter a
//! type's public face over the files of its users.
//!
//! Comments, strings and unit tests (`#[cfg(test)]`) are left out: a
//! comment may point anywhere, and a unit test may check its module with
//! the help of any other (a built-in shape, a refinement to compare with)
//! without the library depending on it.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// One source file: its path below `src/` (with `/`) and its text.
struct Source {
    path: String,
    text: String,
}

#[test]
fn every_module_uses_only_the_modules_before_it() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut sources = Vec::new();
    read_sources(&src, &src, &mut sources);
    assert!(sources.len() > 50, "src/ read: {} files", sources.len());
    let (found, uses) = check(&sources);
    assert!(found.is_empty(), "layering broken:\n{}", found.join("\n"));
    // The check saw the crate's paths: some known uses, none of the ones
    // this layering took away.
    let used = |a: &str, b: &str| uses.contains(&(a.to_string(), b.to_string()));
    for (a, b) in [("repair", "io"), ("surface", "eval"), ("curve", "surface")] {
        assert!(used(a, b), "`{a}` should be seen using `{b}`");
    }
    for (a, b) in [("io", "repair"), ("surface", "snap"), ("surface", "curve")] {
        assert!(!used(a, b), "`{a}` uses `{b}`");
    }
}

#[test]
fn an_upward_path_is_caught_with_its_file_and_line() {
    let lib = "//! Layering: [`a`] then [`b`] then [`c`].\n//!\n\
               pub mod a;\npub mod b;\npub mod c;\npub use c::Thing;\n";
    let cases = [
        ("use crate::c::Thing;", 2),
        ("fn f() {\n    crate::c::g();\n}", 3),
        ("use crate::{a, c};", 2),
        ("use crate::{b::X,\n    c::Y};", 3),
        ("fn f() {\n    super::c::g();\n}", 3),
        ("fn f() -> crate::Thing {\n    todo!()\n}", 2),
    ];
    for (code, line) in cases {
        let sources = [
            source("lib.rs", lib),
            source("a.rs", ""),
            source("b.rs", &format!("//! b.\n{code}\n")),
            source("c.rs", ""),
        ];
        let (found, _) = check(&sources);
        let expected = format!("src/b.rs:{line}: `b` uses `c`");
        assert!(
            found.len() == 1 && found[0].starts_with(&expected),
            "{code}: {found:?}"
        );
    }
    // From a file deeper down, and from a sub-module's super::super.
    let sources = [
        source("lib.rs", lib),
        source("a/mod.rs", "mod inner;\n"),
        source("a/inner.rs", "\nuse super::super::b::X;\n"),
        source("b.rs", ""),
        source("c.rs", ""),
    ];
    let (found, _) = check(&sources);
    assert!(
        found.len() == 1 && found[0].starts_with("src/a/inner.rs:2: `a` uses `b`"),
        "{found:?}"
    );
}

#[test]
fn comments_strings_and_unit_tests_may_point_anywhere() {
    let lib = "//! Layering: [`a`] then [`b`].\n//!\npub mod a;\npub mod b;\n";
    let a = "//! See [`crate::b`].\n\
             /* crate::b::X */\n\
             const S: &str = \"crate::b::X\";\n\
             const R: &str = r#\"super::b\"#;\n\
             fn f<'a>(x: &'a str) -> char { '\"' }\n\
             #[cfg(test)]\nmod tests {\n    use crate::b::X;\n}\n\
             #[cfg(test)]\nmod checks;\n";
    let sources = [
        source("lib.rs", lib),
        source("a.rs", a),
        source("a/checks.rs", "use crate::b::Y;\n"),
        source("b.rs", "use crate::a;\n"),
    ];
    assert_eq!(check(&sources).0, Vec::<String>::new());
}

#[test]
fn a_module_left_out_of_the_list_is_caught() {
    let lib = "//! Layering: [`a`].\n//!\npub mod a;\npub(crate) mod hidden;\n";
    let sources = [
        source("lib.rs", lib),
        source("a.rs", ""),
        source("hidden.rs", ""),
    ];
    let (found, _) = check(&sources);
    assert!(
        found.len() == 1 && found[0].contains("`hidden` is missing from the layer list"),
        "{found:?}"
    );
}

#[test]
fn a_method_added_to_another_module_s_type_is_caught() {
    let lib = "//! Layering: [`a`] then [`b`].\n//!\npub mod a;\npub mod b;\n";
    let sources = [
        source("lib.rs", lib),
        source(
            "a.rs",
            "pub struct Thing<'x>(&'x str);\nimpl<'x> Thing<'x> {}\n",
        ),
        source(
            "b.rs",
            "use crate::a::Thing;\nstruct Own;\nimpl Own {}\n\
             impl std::fmt::Debug for Own {\n    fn fmt(&self) -> impl Sized {}\n}\n\
             impl<'x> crate::a::Thing<'x> {\n    fn more(&self) {}\n}\n",
        ),
    ];
    let (found, _) = check(&sources);
    assert!(
        found.len() == 1
            && found[0].starts_with("src/b.rs:7: `b` adds methods to `Thing`, a type of `a`"),
        "{found:?}"
    );
}

#[test]
fn sub_modules_in_a_cycle_are_caught() {
    let lib = "//! Layering: [`a`].\n//!\npub mod a;\n";
    let sources = [
        source("lib.rs", lib),
        source("a/mod.rs", "mod x;\nmod y;\nmod z;\n"),
        source("a/x.rs", "use super::y::f;\n"),
        source("a/y.rs", "use super::{z, Item};\n"),
        source("a/z.rs", "\nuse crate::a::x::g;\n"),
    ];
    let (found, _) = check(&sources);
    assert!(
        found.len() == 1 && found[0].contains("`a::x` → `a::y` → `a::z` → `a::x`"),
        "{found:?}"
    );
}

fn source(path: &str, text: &str) -> Source {
    Source {
        path: path.to_string(),
        text: text.to_string(),
    }
}

/// Every `.rs` file below `dir`, with its path relative to `root`.
fn read_sources(root: &Path, dir: &Path, out: &mut Vec<Source>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            read_sources(root, &path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            let relative = path.strip_prefix(root).unwrap();
            let parts: Vec<_> = relative.iter().map(|p| p.to_string_lossy()).collect();
            out.push(Source {
                path: parts.join("/"),
                text: std::fs::read_to_string(&path).unwrap(),
            });
        }
    }
}

/// Everything wrong with the layering of `sources` (which hold `lib.rs`),
/// one message per finding, and which module uses which. The findings come
/// in a fixed order: the list's own, upward uses file by file, sub-module
/// cycles, then methods added to other modules' types.
fn check(sources: &[Source]) -> (Vec<String>, BTreeSet<(String, String)>) {
    let lib = &sources
        .iter()
        .find(|s| s.path == "lib.rs")
        .expect("lib.rs")
        .text;
    let mut found = Vec::new();
    let order = layer_list(lib, &mut found);
    let declared = declared_modules(lib);
    found.extend(list_mismatches(&order, &declared));
    let reexports = reexports(lib, &declared);
    let (code, test_only) = library_code(sources);
    let test_only_file = |module: &[String]| test_only.iter().any(|t| module.starts_with(t));
    let references = references(&code, &test_only_file, &declared, &reexports);
    let (uses, upward) = top_level_uses(&references, &order);
    found.extend(upward);
    let modules = library_modules(&code, &test_only_file);
    found.extend(sub_module_cycles(&sub_module_edges(&references, &modules)));
    found.extend(foreign_impls(&code, &test_only_file));
    found.dedup();
    (found, uses)
}

/// Each file's code below `src/` (lib.rs left out), by path: its module,
/// and its text with comments, literals and unit tests blanked.
type Code<'a> = BTreeMap<&'a str, (Vec<String>, String)>;

/// Sub-module uses per parent module: (from, to) → first place.
type SubModuleEdges = BTreeMap<Vec<String>, BTreeMap<(String, String), String>>;

/// One path in the library's code to a module of the crate, resolved.
struct Reference {
    /// Where it is written: "src/file.rs:line".
    place: String,
    /// The top-level module it is written in.
    top: String,
    /// The module it is written in, inline modules included.
    module: Vec<String>,
    /// The absolute module path it leads to.
    target: Vec<String>,
    /// The top-level module it reaches (a re-export counts as its module's).
    used: String,
}

/// The list's disagreements with lib.rs: declared modules it leaves out,
/// then names in it that lib.rs declares no module for.
fn list_mismatches(order: &[String], declared: &BTreeSet<String>) -> Vec<String> {
    let mut found = Vec::new();
    for m in declared {
        if !order.contains(m) {
            found.push(format!(
                "src/lib.rs: module `{m}` is missing from the layer list"
            ));
        }
    }
    for m in order {
        if !declared.contains(m) {
            found.push(format!(
                "src/lib.rs: the layer list names `{m}`, which is no module"
            ));
        }
    }
    found
}

/// The code of every file but lib.rs, and the file modules that exist only
/// for unit tests (`#[cfg(test)] mod checks;`): their code is no library's.
fn library_code(sources: &[Source]) -> (Code<'_>, BTreeSet<Vec<String>>) {
    let mut code = BTreeMap::new();
    let mut test_only = BTreeSet::new();
    for s in sources.iter().filter(|s| s.path != "lib.rs") {
        let module = module_of(&s.path);
        let (text, tests) = without_unit_tests(&without_comments_and_literals(&s.text));
        for name in tests {
            let mut child = module.clone();
            child.push(name);
            test_only.insert(child);
        }
        code.insert(s.path.as_str(), (module, text));
    }
    (code, test_only)
}

/// The modules the library's files hold (unit-test files left out): a path
/// inside a module is a sub-module edge only if it leads to one of these.
fn library_modules(
    code: &Code,
    test_only_file: &dyn Fn(&[String]) -> bool,
) -> BTreeSet<Vec<String>> {
    code.values()
        .filter(|(m, _)| !test_only_file(m))
        .map(|(m, _)| m.clone())
        .collect()
}

/// Every path in the library's code that reaches a module of the crate,
/// file by file in order; paths that climb above the root, or lead to no
/// module (an item of lib.rs's own that it does not re-export), are left
/// out.
fn references(
    code: &Code,
    test_only_file: &dyn Fn(&[String]) -> bool,
    declared: &BTreeSet<String>,
    reexports: &BTreeMap<String, String>,
) -> Vec<Reference> {
    let mut out = Vec::new();
    for (path, (module, text)) in code {
        if test_only_file(module) {
            continue;
        }
        let top = &module[0];
        let inline = inline_modules(text);
        for (at, target) in paths(text) {
            let line = text[..at].matches('\n').count() + 1;
            let mut module = module.clone();
            module.extend(
                inline
                    .iter()
                    .filter(|(span, _)| span.contains(&at))
                    .map(|(_, name)| name.clone()),
            );
            let Some(absolute) = resolve(&module, &target) else {
                continue;
            };
            let Some(used) = top_level_module(&absolute, declared, reexports) else {
                continue;
            };
            out.push(Reference {
                place: format!("src/{path}:{line}"),
                top: top.clone(),
                used: used.clone(),
                module,
                target: absolute,
            });
        }
    }
    out
}

/// The top-level module an absolute path reaches: its first segment, or
/// for a name the crate root re-exports (`crate::Surface`), that name's
/// module. `None` when it reaches no module.
fn top_level_module<'a>(
    absolute: &'a [String],
    declared: &BTreeSet<String>,
    reexports: &'a BTreeMap<String, String>,
) -> Option<&'a String> {
    let first = absolute.first()?;
    if declared.contains(first) {
        Some(first)
    } else {
        reexports.get(first)
    }
}

/// Which top-level module uses which, and a finding for each use of a
/// module that the layer list names after the user.
fn top_level_uses(
    references: &[Reference],
    order: &[String],
) -> (BTreeSet<(String, String)>, Vec<String>) {
    let rank: BTreeMap<&str, usize> = order
        .iter()
        .enumerate()
        .map(|(i, m)| (m.as_str(), i))
        .collect();
    let mut uses = BTreeSet::new();
    let mut found = Vec::new();
    for Reference {
        place, top, used, ..
    } in references.iter().filter(|r| r.used != r.top)
    {
        uses.insert((top.clone(), used.clone()));
        if let (Some(&from), Some(&to)) = (rank.get(top.as_str()), rank.get(used.as_str())) {
            if to > from {
                found.push(format!(
                    "{place}: `{top}` uses `{used}`, which the layer list \
                     in src/lib.rs names after it"
                ));
            }
        }
    }
    (uses, found)
}

/// The uses inside each top-level module, as edges between two children of
/// the deepest module holding both ends (only children that are modules,
/// not items), each with the first place it is seen.
fn sub_module_edges(references: &[Reference], modules: &BTreeSet<Vec<String>>) -> SubModuleEdges {
    let mut inner = SubModuleEdges::new();
    for r in references.iter().filter(|r| r.used == r.top) {
        let (module, absolute) = (&r.module, &r.target);
        let common = module
            .iter()
            .zip(absolute)
            .take_while(|(a, b)| a == b)
            .count();
        if module.len() > common && absolute.len() > common {
            let parent = module[..common].to_vec();
            let mut child = parent.clone();
            child.push(absolute[common].clone());
            if modules.iter().any(|m| m.starts_with(&child)) {
                inner
                    .entry(parent)
                    .or_default()
                    .entry((module[common].clone(), absolute[common].clone()))
                    .or_insert_with(|| r.place.clone());
            }
        }
    }
    inner
}

/// A finding for each parent module whose sub-modules use each other in a
/// cycle, at the place of the cycle's first edge.
fn sub_module_cycles(inner: &SubModuleEdges) -> Vec<String> {
    let mut found = Vec::new();
    for (parent, edges) in inner {
        if let Some(cycle) = find_cycle(edges) {
            let name = |c: &String| format!("`{}::{c}`", parent.join("::"));
            let shown: Vec<String> = cycle.iter().map(name).collect();
            let at = &edges[&(cycle[0].clone(), cycle[1].clone())];
            found.push(format!(
                "{at}: sub-modules use each other in a cycle: {}",
                shown.join(" → ")
            ));
        }
    }
    found
}

/// Inherent `impl` blocks of a type that another top-level module defines
/// (and the block's own module does not), with file and line.
fn foreign_impls(code: &Code, test_only_file: &dyn Fn(&[String]) -> bool) -> Vec<String> {
    let library = || code.iter().filter(|(_, (m, _))| !test_only_file(m));
    let mut defined: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (_, (module, text)) in library() {
        for keyword in ["struct", "enum", "union"] {
            for (_, name) in words_after(text, keyword) {
                defined.entry(name).or_default().insert(module[0].clone());
            }
        }
    }
    let mut found = Vec::new();
    for (path, (module, text)) in library() {
        let top = &module[0];
        for (at, header) in impl_headers(text) {
            let inherent = !header.split_whitespace().any(|w| w == "for");
            let Some(name) = header
                .split(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':'))
                .rfind(|w| !w.is_empty() && !w.starts_with('\''))
                .and_then(|w| w.rsplit("::").next())
            else {
                continue;
            };
            let owners = defined.get(name);
            if inherent
                && owners.is_some_and(|o| !o.contains(top))
                && owners.is_some_and(|o| !o.is_empty())
            {
                let line = text[..at].matches('\n').count() + 1;
                let owners: Vec<String> =
                    owners.unwrap().iter().map(|o| format!("`{o}`")).collect();
                found.push(format!(
                    "src/{path}:{line}: `{top}` adds methods to `{name}`, a type of {}: \
                     a type's methods belong in its own module",
                    owners.join(", ")
                ));
            }
        }
    }
    found
}

/// Each `keyword name` in `code` (whole words): where, and the name.
fn words_after(code: &str, keyword: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let mut from = 0;
    while let Some(k) = code[from..].find(keyword) {
        let at = from + k;
        from = at + keyword.len();
        let before = code[..at].chars().next_back();
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
            continue;
        }
        let rest = &code[from..];
        if !rest.starts_with(char::is_whitespace) {
            continue;
        }
        let name: String = rest
            .trim_start()
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        if !name.is_empty() {
            out.push((at, name));
        }
    }
    out
}

/// Each item-level `impl` in `code`: where, and its header up to the `{`
/// with generic parameters and arguments left out (`impl<'s> A<'s> for B`
/// gives "A for B"). An `impl Trait` in a type (after `->`, `(`, `:` …)
/// is not an item and is skipped.
fn impl_headers(code: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    for (at, _) in words_after(code, "impl")
        .into_iter()
        .chain(impl_with_generics(code))
    {
        let before = code[..at].trim_end().chars().next_back();
        if !matches!(before, None | Some('}' | ';' | '{' | ']')) {
            continue;
        }
        let rest = &code[at + "impl".len()..];
        let mut header = String::new();
        let mut depth = 0;
        for c in rest.chars() {
            match c {
                '<' => depth += 1,
                '>' => depth -= 1,
                '{' if depth == 0 => break,
                _ if depth == 0 => header.push(c),
                _ => {}
            }
        }
        let header = header.split(" where ").next().unwrap_or_default();
        out.push((at, header.trim().to_string()));
    }
    out.sort();
    out.dedup();
    out
}

/// Each `impl<` in `code` (which `words_after` misses: no space).
fn impl_with_generics(code: &str) -> Vec<(usize, String)> {
    code.match_indices("impl<")
        .filter(|(at, _)| {
            !code[..*at]
                .chars()
                .next_back()
                .is_some_and(|c| c.is_alphanumeric() || c == '_')
        })
        .map(|(at, _)| (at, String::new()))
        .collect()
}

/// The modules in the order of the layer list: the backquoted names in the
/// paragraph of lib.rs's doc comment that starts at "Layering". Names given
/// twice are reported.
fn layer_list(lib: &str, found: &mut Vec<String>) -> Vec<String> {
    let doc: Vec<&str> = lib.lines().map_while(|l| l.strip_prefix("//!")).collect();
    let Some(start) = doc.iter().position(|l| l.contains("Layering")) else {
        found.push("src/lib.rs: no \"Layering\" paragraph in the doc comment".to_string());
        return Vec::new();
    };
    let paragraph: Vec<&str> = doc[start..]
        .iter()
        .take_while(|l| !l.trim().is_empty())
        .copied()
        .collect();
    let mut order: Vec<String> = Vec::new();
    for (i, piece) in paragraph.join(" ").split('`').enumerate() {
        let is_name = piece.starts_with(|c: char| c.is_ascii_lowercase())
            && piece
                .chars()
                .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_');
        if i % 2 == 1 && is_name {
            if order.iter().any(|m| m == piece) {
                found.push(format!("src/lib.rs: the layer list names `{piece}` twice"));
            } else {
                order.push(piece.to_string());
            }
        }
    }
    order
}

/// The modules lib.rs declares (`mod x;`, public or not).
fn declared_modules(lib: &str) -> BTreeSet<String> {
    lib.lines()
        .filter_map(|l| {
            let l = l.trim();
            let l = l
                .strip_prefix("pub(crate) ")
                .or_else(|| l.strip_prefix("pub "))
                .unwrap_or(l);
            l.strip_prefix("mod ")?
                .strip_suffix(';')
                .map(str::to_string)
        })
        .collect()
}

/// The crate root's re-exports of module items: name → module.
fn reexports(lib: &str, declared: &BTreeSet<String>) -> BTreeMap<String, String> {
    let mut out = BTreeMap::new();
    for l in lib.lines() {
        let Some(rest) = l.trim().strip_prefix("pub use ") else {
            continue;
        };
        let Some((module, items)) = rest.trim_end_matches(';').split_once("::") else {
            continue;
        };
        if !declared.contains(module) {
            continue;
        }
        for item in items.trim_matches(|c| c == '{' || c == '}').split(',') {
            let name = item.rsplit(" as ").next().unwrap().trim();
            let name = name.rsplit("::").next().unwrap();
            if !name.is_empty() {
                out.insert(name.to_string(), module.to_string());
            }
        }
    }
    out
}

/// The module a file holds: `snap/index.rs` is `snap::index`,
/// `snap/mod.rs` is `snap`.
fn module_of(path: &str) -> Vec<String> {
    let mut parts: Vec<String> = path
        .trim_end_matches(".rs")
        .split('/')
        .map(str::to_string)
        .collect();
    if parts.last().is_some_and(|p| p == "mod") {
        parts.pop();
    }
    parts
}

/// `text` with comments, string and character literals blanked (newlines
/// kept, so lines still count), leaving lifetimes.
fn without_comments_and_literals(text: &str) -> String {
    let c: Vec<char> = text.chars().collect();
    let mut out = c.clone();
    let blank = |out: &mut Vec<char>, a: usize, b: usize| {
        for x in &mut out[a..b.min(c.len())] {
            if *x != '\n' {
                *x = ' ';
            }
        }
    };
    let ident = |i: usize| c[i].is_alphanumeric() || c[i] == '_';
    let mut i = 0;
    while i < c.len() {
        let next = |k: usize| c.get(i + k).copied().unwrap_or('\0');
        if c[i] == '/' && next(1) == '/' {
            let end = (i..c.len()).find(|&j| c[j] == '\n').unwrap_or(c.len());
            blank(&mut out, i, end);
            i = end;
        } else if c[i] == '/' && next(1) == '*' {
            let (mut depth, mut j) = (0, i);
            while j < c.len() {
                if c[j] == '/' && c.get(j + 1) == Some(&'*') {
                    depth += 1;
                    j += 2;
                } else if c[j] == '*' && c.get(j + 1) == Some(&'/') {
                    depth -= 1;
                    j += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    j += 1;
                }
            }
            blank(&mut out, i, j);
            i = j;
        } else if (c[i] == 'r' || (c[i] == 'b' && next(1) == 'r')) && (i == 0 || !ident(i - 1)) && {
            let k = if c[i] == 'b' { 2 } else { 1 };
            let hashes = (i + k..c.len()).take_while(|&j| c[j] == '#').count();
            c.get(i + k + hashes) == Some(&'"')
        } {
            let k = if c[i] == 'b' { 2 } else { 1 };
            let hashes = (i + k..c.len()).take_while(|&j| c[j] == '#').count();
            let mut j = i + k + hashes + 1;
            while j < c.len() && !(c[j] == '"' && (1..=hashes).all(|h| c.get(j + h) == Some(&'#')))
            {
                j += 1;
            }
            let end = j + 1 + hashes;
            blank(&mut out, i, end);
            i = end;
        } else if c[i] == '"' {
            let mut j = i + 1;
            while j < c.len() && c[j] != '"' {
                j += if c[j] == '\\' { 2 } else { 1 };
            }
            blank(&mut out, i, j + 1);
            i = j + 1;
        } else if c[i] == '\'' && next(1) == '\\' {
            let end = (i + 2..c.len()).find(|&j| c[j] == '\'').unwrap_or(c.len());
            blank(&mut out, i, end + 1);
            i = end + 1;
        } else if c[i] == '\'' && next(2) == '\'' {
            blank(&mut out, i, i + 3);
            i += 3;
        } else {
            i += 1;
        }
    }
    out.into_iter().collect()
}

/// `code` with every item under `#[cfg(test)]` blanked, and the names of
/// the file modules declared that way (`#[cfg(test)] mod checks;`).
fn without_unit_tests(code: &str) -> (String, Vec<String>) {
    const ATTRIBUTE: &str = "#[cfg(test)]";
    let mut c: Vec<char> = code.chars().collect();
    let mut names = Vec::new();
    let mut from = 0;
    loop {
        let text: String = c[from..].iter().collect();
        let Some(offset) = text.find(ATTRIBUTE) else {
            break;
        };
        let start = from + text[..offset].chars().count();
        let mut j = start + ATTRIBUTE.len();
        while j < c.len() && c[j] != '{' && c[j] != ';' {
            j += 1;
        }
        let end = if j < c.len() && c[j] == '{' {
            let mut depth = 0;
            loop {
                match c[j] {
                    '{' => depth += 1,
                    '}' => depth -= 1,
                    _ => {}
                }
                if depth == 0 {
                    break j + 1;
                }
                j += 1;
            }
        } else {
            let item: String = c[start + ATTRIBUTE.len()..j].iter().collect();
            let words: Vec<&str> = item.split_whitespace().collect();
            if let [.., "mod", name] = words.as_slice() {
                names.push(name.to_string());
            }
            (j + 1).min(c.len())
        };
        for x in &mut c[start..end] {
            if *x != '\n' {
                *x = ' ';
            }
        }
        from = end;
    }
    (c.into_iter().collect(), names)
}

/// Every path that starts at `crate`, `super` or `self` in `code`: where it
/// is (a byte offset; a group's entry is where the entry is) and its
/// segments, with `use` groups expanded: `use crate::{a, b::c}` gives
/// `crate::a` and `crate::b::c`.
fn paths(code: &str) -> Vec<(usize, Vec<String>)> {
    let c: Vec<char> = code.chars().collect();
    let bytes: Vec<usize> = code.char_indices().map(|(b, _)| b).collect();
    let ident = |i: usize| i < c.len() && (c[i].is_alphanumeric() || c[i] == '_');
    let mut out = Vec::new();
    let mut i = 0;
    while i < c.len() {
        if ident(i) && (i == 0 || !(ident(i - 1) || c[i - 1] == '$' || c[i - 1] == ':')) {
            let end = (i..c.len()).find(|&j| !ident(j)).unwrap_or(c.len());
            let word: String = c[i..end].iter().collect();
            let after = skip_space(&c, end);
            if matches!(word.as_str(), "crate" | "super" | "self")
                && c.get(after) == Some(&':')
                && c.get(after + 1) == Some(&':')
            {
                let mut found = Vec::new();
                let stop = use_tree(&c, after + 2, (i, vec![word]), &mut found);
                out.extend(found.into_iter().map(|(at, p)| (bytes[at], p)));
                i = stop;
                continue;
            }
            i = end;
        } else {
            i += 1;
        }
    }
    out
}

fn skip_space(c: &[char], mut i: usize) -> usize {
    while i < c.len() && c[i].is_whitespace() {
        i += 1;
    }
    i
}

/// Reads the rest of a path after `prefix::` from `i`: a segment and more,
/// a `{…}` group of such rests, or `*`. The prefix comes with where its
/// path (or group entry) starts. Returns where it stopped.
fn use_tree(
    c: &[char],
    i: usize,
    prefix: (usize, Vec<String>),
    out: &mut Vec<(usize, Vec<String>)>,
) -> usize {
    let mut i = skip_space(c, i);
    if c.get(i) == Some(&'{') {
        i += 1;
        loop {
            i = skip_space(c, i);
            match c.get(i) {
                None => return i,
                Some('}') => return i + 1,
                Some(',') => i += 1,
                _ => {
                    let before = i;
                    i = use_tree(c, i, (i, prefix.1.clone()), out);
                    if i == before {
                        i += 1;
                    }
                }
            }
        }
    }
    let start = i;
    while i < c.len() && (c[i].is_alphanumeric() || c[i] == '_') {
        i += 1;
    }
    let mut path = prefix;
    if i > start {
        path.1.push(c[start..i].iter().collect());
        let after = skip_space(c, i);
        if c.get(after) == Some(&':') && c.get(after + 1) == Some(&':') {
            return use_tree(c, after + 2, path, out);
        }
    } else if c.get(i) == Some(&'*') {
        i += 1;
    }
    out.push(path);
    i
}

/// The modules written inline in `code` (`mod name { … }`): where each
/// spans (byte offsets) and its name, outer ones first.
fn inline_modules(code: &str) -> Vec<(std::ops::Range<usize>, String)> {
    let mut out = Vec::new();
    let mut from = 0;
    while let Some(k) = code[from..].find("mod ") {
        let start = from + k;
        from = start + 4;
        if code[..start].ends_with(|c: char| c.is_alphanumeric() || c == '_') {
            continue;
        }
        let rest = &code[from..];
        let name: String = rest
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        if name.is_empty() || !rest[name.len()..].trim_start().starts_with('{') {
            continue;
        }
        let open = from + name.len() + rest[name.len()..].find('{').unwrap();
        let mut depth = 0;
        let mut end = code.len();
        for (j, ch) in code[open..].char_indices() {
            match ch {
                '{' => depth += 1,
                '}' => depth -= 1,
                _ => continue,
            }
            if depth == 0 {
                end = open + j + 1;
                break;
            }
        }
        out.push((start..end, name));
    }
    out
}

/// The absolute module path of `path` (which starts at `crate`, `super` or
/// `self`) used from inside `module`; `None` when it climbs above the root.
fn resolve(module: &[String], path: &[String]) -> Option<Vec<String>> {
    let mut at: Vec<String> = match path[0].as_str() {
        "crate" => Vec::new(),
        _ => module.to_vec(),
    };
    let mut rest = &path[1..];
    if path[0] == "super" {
        at.pop()?;
    }
    while rest.first().is_some_and(|s| s == "super") {
        at.pop()?;
        rest = &rest[1..];
    }
    at.extend(rest.iter().filter(|s| *s != "self").cloned());
    Some(at)
}

/// A cycle among the edges (first node repeated at the end), if any.
fn find_cycle(edges: &BTreeMap<(String, String), String>) -> Option<Vec<String>> {
    let mut next: BTreeMap<&str, Vec<&str>> = BTreeMap::new();
    for (a, b) in edges.keys() {
        next.entry(a.as_str()).or_default().push(b.as_str());
    }
    fn visit<'a>(
        node: &'a str,
        next: &BTreeMap<&'a str, Vec<&'a str>>,
        done: &mut BTreeSet<&'a str>,
        trail: &mut Vec<&'a str>,
    ) -> Option<Vec<String>> {
        if let Some(k) = trail.iter().position(|&n| n == node) {
            let mut cycle: Vec<String> = trail[k..].iter().map(|s| s.to_string()).collect();
            cycle.push(node.to_string());
            return Some(cycle);
        }
        if !done.insert(node) {
            return None;
        }
        trail.push(node);
        for &n in next.get(node).into_iter().flatten() {
            if let Some(cycle) = visit(n, next, done, trail) {
                return Some(cycle);
            }
        }
        trail.pop();
        None
    }
    let mut done = BTreeSet::new();
    for &start in next.keys() {
        if let Some(cycle) = visit(start, &next, &mut done, &mut Vec::new()) {
            return Some(cycle);
        }
    }
    None
}
