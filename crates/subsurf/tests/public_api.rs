//! The public API of `subsurf`, listed in `crates/subsurf/api.txt` and reviewed there: every
//! item a user can name (modules, types, functions, constants, re-exports), every public field
//! and enum variant, and every public method of a public type. This test lists the API from the
//! sources and fails on any difference, so an accidental new public item (or a removed one)
//! shows up in review as a change of `api.txt`. After a deliberate change:
//! `SUBSURF_BLESS=1 cargo test -p subsurf --test public_api` writes the new list.

use std::collections::{BTreeSet, HashMap};
use std::path::{Path, PathBuf};
use syn::{Item, UseTree, Visibility};

/// One module of the crate: its items as parsed, and where it is.
struct Module {
    /// `crate::a::b` as `["a", "b"]`.
    path: Vec<String>,
    items: Vec<Item>,
}

/// Whether `vis` is plain `pub` (not `pub(crate)`, `pub(super)`, private).
fn is_pub(vis: &Visibility) -> bool {
    matches!(vis, Visibility::Public(_))
}

fn has_cfg_test(attrs: &[syn::Attribute]) -> bool {
    attrs.iter().any(|a| {
        a.path().is_ident("cfg")
            && a.meta
                .require_list()
                .is_ok_and(|l| l.tokens.to_string().contains("test"))
    })
}

/// Loads module `path` from `file` (and every module below it, from its directory `dir`).
fn load(path: Vec<String>, items: Vec<Item>, dir: &Path, out: &mut Vec<Module>) {
    for item in &items {
        let Item::Mod(m) = item else { continue };
        if has_cfg_test(&m.attrs) {
            continue;
        }
        let mut sub = path.clone();
        sub.push(m.ident.to_string().trim_start_matches("r#").to_string());
        let name = sub.last().unwrap().clone();
        match &m.content {
            Some((_, inline)) => load(sub, inline.clone(), &dir.join(&name), out),
            None => {
                let (file, subdir) = if dir.join(format!("{name}.rs")).exists() {
                    (dir.join(format!("{name}.rs")), dir.join(&name))
                } else {
                    (dir.join(&name).join("mod.rs"), dir.join(&name))
                };
                let text = std::fs::read_to_string(&file)
                    .unwrap_or_else(|e| panic!("{}: {e}", file.display()));
                let parsed =
                    syn::parse_file(&text).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
                load(sub, parsed.items, &subdir, out);
            }
        }
    }
    out.push(Module { path, items });
}

/// What a public name stands for.
#[derive(Clone, Debug)]
enum Target {
    /// An item defined in module `module` (its path) with this identifier and kind.
    Item {
        module: Vec<String>,
        ident: String,
        kind: &'static str,
    },
    /// A module.
    Module(Vec<String>),
}

struct Crate {
    modules: HashMap<Vec<String>, Vec<Item>>,
}

fn kind_and_ident(item: &Item) -> Option<(&'static str, String, &Visibility)> {
    Some(match item {
        Item::Fn(f) => ("fn", f.sig.ident.to_string(), &f.vis),
        Item::Struct(s) => ("struct", s.ident.to_string(), &s.vis),
        Item::Enum(e) => ("enum", e.ident.to_string(), &e.vis),
        Item::Trait(t) => ("trait", t.ident.to_string(), &t.vis),
        Item::Const(c) => ("const", c.ident.to_string(), &c.vis),
        Item::Static(s) => ("static", s.ident.to_string(), &s.vis),
        Item::Type(t) => ("type", t.ident.to_string(), &t.vis),
        Item::Union(u) => ("union", u.ident.to_string(), &u.vis),
        Item::Mod(m) => ("mod", m.ident.to_string(), &m.vis),
        _ => return None,
    })
}

impl Crate {
    /// Resolves the name `name` as seen from module `from` (its definitions and `use`s), any
    /// visibility: the crate's own view, for following re-exports.
    fn resolve(&self, from: &[String], segments: &[String], depth: usize) -> Option<Target> {
        assert!(depth < 32, "re-export cycle at {from:?} {segments:?}");
        let (first, rest) = segments.split_first()?;
        let mut base: Vec<String> = match first.as_str() {
            "crate" => Vec::new(),
            "self" => from.to_vec(),
            "super" => from[..from.len() - 1].to_vec(),
            _ => {
                // A name defined or imported in `from`.
                let t = self.lookup(from, first, depth)?;
                if rest.is_empty() {
                    return Some(t);
                }
                match t {
                    Target::Module(m) => m,
                    Target::Item { .. } => return None, // an associated item: not followed
                }
            }
        };
        let mut rest = rest;
        while let Some((s, r)) = rest.split_first() {
            if s == "super" {
                base.pop();
                rest = r;
            } else {
                break;
            }
        }
        if rest.is_empty() {
            return Some(Target::Module(base));
        }
        self.resolve_in(&base, rest, depth + 1)
    }

    /// `segments` inside module `module`.
    fn resolve_in(&self, module: &[String], segments: &[String], depth: usize) -> Option<Target> {
        let (first, rest) = segments.split_first()?;
        let t = self.lookup(module, first, depth)?;
        if rest.is_empty() {
            return Some(t);
        }
        match t {
            Target::Module(m) => self.resolve_in(&m, rest, depth + 1),
            Target::Item { .. } => None,
        }
    }

    /// The name `name` in module `module`: a definition, a submodule or a `use`.
    fn lookup(&self, module: &[String], name: &str, depth: usize) -> Option<Target> {
        let items = self.modules.get(module)?;
        for item in items {
            if let Some((kind, ident, _)) = kind_and_ident(item) {
                if ident.trim_start_matches("r#") == name {
                    if kind == "mod" {
                        let mut m = module.to_vec();
                        m.push(name.to_string());
                        return Some(Target::Module(m));
                    }
                    return Some(Target::Item {
                        module: module.to_vec(),
                        ident,
                        kind,
                    });
                }
            }
        }
        for item in items {
            let Item::Use(u) = item else { continue };
            for (alias, path) in flatten_use(&u.tree, Vec::new()) {
                if alias.as_deref() == Some(name) {
                    return self.resolve(module, &path, depth + 1);
                }
            }
        }
        // Items of external crates and the prelude are not the crate's.
        None
    }
}

/// The leaves of a use tree: `(Some(name), path)` for a name, `(None, path)` for a glob.
fn flatten_use(tree: &UseTree, prefix: Vec<String>) -> Vec<(Option<String>, Vec<String>)> {
    let mut out = Vec::new();
    match tree {
        UseTree::Path(p) => {
            let mut pre = prefix;
            pre.push(p.ident.to_string());
            out.extend(flatten_use(&p.tree, pre));
        }
        UseTree::Name(n) => {
            let mut path = prefix;
            let name = n.ident.to_string();
            if name == "self" {
                let alias = path.last().cloned();
                out.push((alias, path));
            } else {
                path.push(name.clone());
                out.push((Some(name), path));
            }
        }
        UseTree::Rename(r) => {
            let mut path = prefix;
            path.push(r.ident.to_string());
            out.push((Some(r.rename.to_string()), path));
        }
        UseTree::Glob(_) => out.push((None, prefix)),
        UseTree::Group(g) => {
            for t in &g.items {
                out.extend(flatten_use(t, prefix.clone()));
            }
        }
    }
    out
}

fn type_ident(ty: &syn::Type) -> Option<String> {
    match ty {
        syn::Type::Path(p) => p.path.segments.last().map(|s| s.ident.to_string()),
        _ => None,
    }
}

/// The public API as sorted lines.
fn api() -> Vec<String> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let root = syn::parse_file(&std::fs::read_to_string(src.join("lib.rs")).unwrap()).unwrap();
    let mut modules = Vec::new();
    load(Vec::new(), root.items, &src, &mut modules);
    let krate = Crate {
        modules: modules.into_iter().map(|m| (m.path, m.items)).collect(),
    };

    // Public names, walked from the root: (public path, target).
    let mut public: Vec<(Vec<String>, Target)> = Vec::new();
    let mut stack = vec![(Vec::<String>::new(), Vec::<String>::new())]; // (public path, module)
    let mut seen_modules = BTreeSet::new();
    while let Some((pub_path, module)) = stack.pop() {
        if !seen_modules.insert(pub_path.clone()) {
            continue;
        }
        let items = &krate.modules[&module];
        for item in items {
            if let Item::Use(u) = item {
                if !is_pub(&u.vis) {
                    continue;
                }
                for (alias, path) in flatten_use(&u.tree, Vec::new()) {
                    let Some(target) = krate.resolve(&module, &path, 0) else {
                        // A re-export of another crate's item (none today).
                        let mut p = pub_path.clone();
                        p.push(alias.unwrap_or_else(|| "*".into()));
                        public.push((
                            p,
                            Target::Item {
                                module: Vec::new(),
                                ident: path.join("::"),
                                kind: "extern",
                            },
                        ));
                        continue;
                    };
                    match (alias, target) {
                        (Some(a), Target::Module(m)) => {
                            let mut p = pub_path.clone();
                            p.push(a);
                            public.push((p.clone(), Target::Module(m.clone())));
                            stack.push((p, m));
                        }
                        (Some(a), t) => {
                            let mut p = pub_path.clone();
                            p.push(a);
                            public.push((p, t));
                        }
                        (None, Target::Module(m)) => {
                            // A glob: every public name of that module.
                            for it in &krate.modules[&m] {
                                if let Some((kind, ident, vis)) = kind_and_ident(it) {
                                    if is_pub(vis) && kind != "mod" {
                                        let mut p = pub_path.clone();
                                        p.push(ident.clone());
                                        public.push((
                                            p,
                                            Target::Item {
                                                module: m.clone(),
                                                ident,
                                                kind,
                                            },
                                        ));
                                    }
                                }
                            }
                        }
                        (None, _) => {}
                    }
                }
                continue;
            }
            let Some((kind, ident, vis)) = kind_and_ident(item) else {
                continue;
            };
            if !is_pub(vis) {
                continue;
            }
            if let Item::Mod(m) = item {
                if has_cfg_test(&m.attrs) {
                    continue;
                }
            }
            let name = ident.trim_start_matches("r#").to_string();
            let mut p = pub_path.clone();
            p.push(name.clone());
            if kind == "mod" {
                let mut m = module.clone();
                m.push(name);
                public.push((p.clone(), Target::Module(m.clone())));
                stack.push((p, m));
            } else {
                public.push((
                    p,
                    Target::Item {
                        module: module.clone(),
                        ident,
                        kind,
                    },
                ));
            }
        }
    }

    // Public types by their definition, for fields, variants and methods.
    let mut types: HashMap<(Vec<String>, String), Vec<String>> = HashMap::new();
    let mut lines = BTreeSet::new();
    for (p, t) in &public {
        let name = format!("subsurf::{}", p.join("::"));
        match t {
            Target::Module(_) => {
                lines.insert(format!("mod {name}"));
            }
            Target::Item {
                module,
                ident,
                kind,
            } => {
                lines.insert(format!("{kind} {name}"));
                if matches!(*kind, "struct" | "enum" | "trait") {
                    types
                        .entry((module.clone(), ident.clone()))
                        .or_default()
                        .push(name);
                }
            }
        }
    }
    for (module, items) in &krate.modules {
        for item in items {
            // `#[macro_export]` macros are at the crate root wherever they are defined.
            if let Item::Macro(m) = item {
                if m.attrs.iter().any(|a| a.path().is_ident("macro_export")) {
                    if let Some(id) = &m.ident {
                        lines.insert(format!("macro subsurf::{id}"));
                    }
                }
            }
            match item {
                Item::Struct(s) => {
                    let Some(names) = types.get(&(module.clone(), s.ident.to_string())) else {
                        continue;
                    };
                    for f in &s.fields {
                        if let (true, Some(id)) = (is_pub(&f.vis), &f.ident) {
                            for n in names {
                                lines.insert(format!("field {n}.{id}"));
                            }
                        }
                    }
                }
                Item::Enum(e) => {
                    let Some(names) = types.get(&(module.clone(), e.ident.to_string())) else {
                        continue;
                    };
                    for v in &e.variants {
                        if has_cfg_test(&v.attrs) {
                            continue;
                        }
                        for n in names {
                            lines.insert(format!("variant {n}::{}", v.ident));
                        }
                    }
                }
                Item::Trait(t) => {
                    let Some(names) = types.get(&(module.clone(), t.ident.to_string())) else {
                        continue;
                    };
                    for ti in &t.items {
                        if let syn::TraitItem::Fn(f) = ti {
                            for n in names {
                                lines.insert(format!("method {n}::{}", f.sig.ident));
                            }
                        }
                    }
                }
                Item::Impl(imp) if imp.trait_.is_none() => {
                    let Some(ty) = type_ident(&imp.self_ty) else {
                        continue;
                    };
                    // The type the impl names, as its module sees it.
                    let Some(Target::Item {
                        module: def, ident, ..
                    }) = krate.resolve(module, &[ty], 0)
                    else {
                        continue;
                    };
                    let Some(names) = types.get(&(def, ident)) else {
                        continue;
                    };
                    for ii in &imp.items {
                        let (id, vis, attrs) = match ii {
                            syn::ImplItem::Fn(f) => (f.sig.ident.to_string(), &f.vis, &f.attrs),
                            syn::ImplItem::Const(c) => (c.ident.to_string(), &c.vis, &c.attrs),
                            _ => continue,
                        };
                        if is_pub(vis) && !has_cfg_test(attrs) {
                            for n in names {
                                lines.insert(format!("method {n}::{id}"));
                            }
                        }
                    }
                }
                _ => {}
            }
        }
    }
    lines.into_iter().collect()
}

fn api_file() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("api.txt")
}

#[test]
fn the_public_api_is_the_reviewed_list() {
    let got = api();
    let text = format!(
        "# The public API of subsurf, one item per line (tests/public_api.rs).\n\
         # Regenerate after a deliberate change: SUBSURF_BLESS=1 cargo test -p subsurf --test public_api\n{}\n",
        got.join("\n")
    );
    if std::env::var_os("SUBSURF_BLESS").is_some() {
        std::fs::write(api_file(), &text).unwrap();
        return;
    }
    let want = std::fs::read_to_string(api_file()).unwrap_or_default();
    let want: BTreeSet<&str> = want.lines().filter(|l| !l.starts_with('#')).collect();
    let got_set: BTreeSet<&str> = got.iter().map(String::as_str).collect();
    let added: Vec<_> = got_set.difference(&want).collect();
    let removed: Vec<_> = want.difference(&got_set).collect();
    assert!(
        added.is_empty() && removed.is_empty(),
        "the public API differs from crates/subsurf/api.txt (review, then bless with \
         SUBSURF_BLESS=1):\nnew:\n  {}\ngone:\n  {}",
        added
            .iter()
            .map(|s| s.to_string())
            .collect::<Vec<_>>()
            .join("\n  "),
        removed
            .iter()
            .map(|s| s.to_string())
            .collect::<Vec<_>>()
            .join("\n  ")
    );
}

/// The lister sees what it must: re-exported items under their public path, no
/// implementation module of `limit`, fields through accessors only.
#[test]
fn the_lister_follows_re_exports_and_hides_private_modules() {
    let api = api();
    let has = |l: &str| api.iter().any(|a| a == l);
    assert!(
        has("struct subsurf::limit::PatchTable"),
        "re-export followed"
    );
    assert!(has("method subsurf::limit::PatchTable::num_patches"));
    assert!(has("struct subsurf::Topology"));
    assert!(has("field subsurf::Mesh.positions"));
    assert!(has("variant subsurf::Scheme::Loop"));
    assert!(!api.iter().any(|a| a.starts_with("mod subsurf::limit::")));
    assert!(!api
        .iter()
        .any(|a| a.starts_with("field subsurf::limit::PatchTable.")));
    assert!(!api
        .iter()
        .any(|a| a.starts_with("field subsurf::Topology.")));
}
