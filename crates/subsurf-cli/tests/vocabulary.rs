//! `docs/vocabulary.md` holds: every flag of every `--help` is in the concept table, with the
//! commands it applies to; no old spelling is shown; the old spellings still parse (hidden
//! aliases); the values `--help` lists are the table's, and the library's option enums name
//! their values as the table does.

mod common;

use common::{bin, repo, run_ok, tmp};
use std::collections::{BTreeMap, BTreeSet};
use subsurf::OptionValue;

const COMMANDS: [&str; 9] = [
    "info", "refine", "bench", "render", "compare", "prep", "gpu-info", "limit", "eval",
];

/// One row of the concept table.
#[derive(Debug)]
struct Row {
    concept: String,
    cli_flag: Option<String>,
    commands: Vec<String>,
    python_keyword: Vec<String>,
    values: Vec<String>,
    /// Old spellings, each with the commands that still read it (CLI aliases).
    old_names: Vec<(String, Vec<String>)>,
}

/// The spans between backticks of a cell.
fn code_spans(cell: &str) -> Vec<String> {
    cell.split('`')
        .enumerate()
        .filter(|(k, _)| k % 2 == 1)
        .map(|(_, s)| s.to_string())
        .collect()
}

/// The old names of a cell: `` `--samples` (eval), `n` ``; an old flag is read by the
/// commands in parentheses after it, else by all of the row's `commands`.
fn old_names(cell: &str, commands: &[String]) -> Vec<(String, Vec<String>)> {
    let parts: Vec<&str> = cell.split('`').collect();
    (1..parts.len())
        .step_by(2)
        .map(|k| {
            let after = parts.get(k + 1).copied().unwrap_or("");
            let cmds = match (after.find('('), after.find(')')) {
                (Some(a), Some(b)) if a < b => after[a + 1..b]
                    .split(',')
                    .map(|s| s.trim().to_string())
                    .collect(),
                _ => commands.to_vec(),
            };
            (parts[k].to_string(), cmds)
        })
        .collect()
}

/// The rows between the `vocabulary:begin` and `vocabulary:end` markers.
fn table() -> Vec<Row> {
    let text = std::fs::read_to_string(repo("docs/vocabulary.md")).unwrap();
    let start = text
        .find("<!-- vocabulary:begin -->")
        .expect("begin marker");
    let end = text.find("<!-- vocabulary:end -->").expect("end marker");
    let lines: Vec<&str> = text[start..end]
        .lines()
        .filter(|l| l.starts_with('|'))
        .collect();
    let header: Vec<&str> = lines[0]
        .trim_matches('|')
        .split('|')
        .map(str::trim)
        .collect();
    assert_eq!(
        header,
        [
            "Concept",
            "Rust",
            "CLI flag",
            "Commands",
            "Python keyword",
            "Python",
            "File",
            "Values",
            "Old names"
        ]
    );
    lines[2..]
        .iter()
        .map(|l| {
            let c: Vec<&str> = l.trim_matches('|').split('|').map(str::trim).collect();
            assert_eq!(c.len(), header.len(), "{l}");
            let commands = if c[3] == "—" {
                Vec::new()
            } else if c[3] == "all" {
                COMMANDS.iter().map(|s| s.to_string()).collect()
            } else {
                c[3].split(',').map(|s| s.trim().to_string()).collect()
            };
            let cli_flag = code_spans(c[2]).into_iter().next();
            assert_eq!(
                cli_flag.is_some(),
                !commands.is_empty(),
                "{l}: a flag needs its commands"
            );
            Row {
                concept: c[0].to_string(),
                cli_flag,
                python_keyword: code_spans(c[4]),
                values: code_spans(c[7]),
                old_names: old_names(c[8], &commands),
                commands,
            }
        })
        .collect()
}

/// `subsurf COMMAND --help`.
fn help(command: &str) -> String {
    let out = run_ok(bin().args([command, "--help"]));
    String::from_utf8(out.stdout).unwrap()
}

/// The long flags `--help` lists (`--help` itself left out).
fn flags(help: &str) -> BTreeSet<String> {
    help.lines()
        .filter_map(|l| {
            let t = l.trim_start();
            let t = match t.strip_prefix('-') {
                Some(r) if !r.starts_with('-') && r.len() > 3 && &r[1..3] == ", " => &r[3..],
                _ => t,
            };
            let name: String = t
                .strip_prefix("--")?
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '-')
                .collect();
            (l.starts_with("  ") && !name.is_empty()).then(|| format!("--{name}"))
        })
        .filter(|f| f != "--help" && f != "--version")
        .collect()
}

/// The `[possible values: ...]` of `flag` in `help`.
fn possible_values(help: &str, flag: &str) -> Option<Vec<String>> {
    let mut inside = false;
    for l in help.lines() {
        let t = l.trim_start();
        let is_flag_line = l.starts_with("  ") && t.starts_with('-');
        if is_flag_line {
            inside = t.starts_with(flag)
                && !t[flag.len()..].starts_with(|c: char| c.is_ascii_alphanumeric() || c == '-')
                || t.contains(&format!(", {flag} "));
            continue;
        }
        if inside {
            if let Some(v) = t.strip_prefix("[possible values: ") {
                let v = v.trim_end_matches(']');
                return Some(v.split(", ").map(str::to_string).collect());
            }
        }
    }
    None
}

/// Whether `text` mentions `flag` as a whole word.
fn mentions(text: &str, flag: &str) -> bool {
    text.match_indices(flag).any(|(k, _)| {
        !text[k + flag.len()..].starts_with(|c: char| c.is_ascii_alphanumeric() || c == '-')
    })
}

#[test]
fn help_matches_the_table() {
    let rows = table();
    let helps: BTreeMap<&str, String> = COMMANDS.iter().map(|&c| (c, help(c))).collect();
    // Every flag of the table where the table puts it, its values as the table lists them.
    for row in &rows {
        let Some(flag) = &row.cli_flag else { continue };
        for cmd in &row.commands {
            let h = helps
                .get(cmd.as_str())
                .unwrap_or_else(|| panic!("{}: no command {cmd}", row.concept));
            assert!(
                flags(h).contains(flag),
                "{}: `subsurf {cmd} --help` has no {flag}",
                row.concept
            );
            if !row.values.is_empty() {
                assert_eq!(
                    possible_values(h, flag).as_ref(),
                    Some(&row.values),
                    "subsurf {cmd} {flag}: the values of docs/vocabulary.md"
                );
            }
        }
    }
    // Every flag of every command is in the table, for that command.
    for (cmd, h) in &helps {
        for flag in flags(h) {
            assert!(
                rows.iter()
                    .any(|r| r.cli_flag.as_deref() == Some(flag.as_str())
                        && r.commands.iter().any(|c| c == cmd)),
                "subsurf {cmd} {flag}: not in docs/vocabulary.md for {cmd}"
            );
        }
    }
    // No old spelling is shown.
    for row in &rows {
        for (old, _) in row.old_names.iter().filter(|(o, _)| o.starts_with("--")) {
            for (cmd, h) in &helps {
                assert!(
                    !mentions(h, old),
                    "subsurf {cmd} --help shows the old {old} ({})",
                    row.concept
                );
            }
        }
    }
}

#[test]
fn old_spellings_still_parse() {
    // clap parses in order: a flag it does not know fails before `--help` is reached.
    let unknown = bin()
        .args(["eval", "--no-such-flag", "3", "--help"])
        .output()
        .unwrap();
    assert!(!unknown.status.success());
    let mut checked = 0;
    for row in table() {
        for (old, commands) in row.old_names.iter().filter(|(o, _)| o.starts_with("--")) {
            let value = row.values.first().cloned().unwrap_or_else(|| "3".into());
            for cmd in commands {
                let out = bin()
                    .args([cmd.as_str(), old.as_str(), value.as_str(), "--help"])
                    .output()
                    .unwrap();
                assert!(
                    out.status.success(),
                    "subsurf {cmd} {old} {value}: {}",
                    String::from_utf8_lossy(&out.stderr)
                );
                checked += 1;
            }
        }
    }
    assert!(checked >= 4, "{checked} old spellings");
}

/// The output of `subsurf ARGS -o FILE`, read back.
fn output_of(args: &[&str], name: &str) -> Vec<u8> {
    let out = tmp(name);
    run_ok(bin().args(args).arg("-o").arg(&out));
    std::fs::read(out).unwrap()
}

#[test]
fn old_spellings_do_what_the_new_ones_do() {
    let car = repo("examples/car.obj");
    let car = car.to_str().unwrap();
    assert_eq!(
        output_of(&["eval", car, "--samples", "3"], "old_eval.txt"),
        output_of(&["eval", car, "--tess", "3"], "new_eval.txt")
    );
    let uv = repo("testdata/shapes/catmark_pyramid.obj");
    let uv = uv.to_str().unwrap();
    let old = [
        "refine",
        uv,
        "-l",
        "1",
        "--uv-interp",
        "corners-only",
        "--triangles",
        "smooth",
    ];
    let new = [
        "refine",
        uv,
        "-l",
        "1",
        "--uv-interpolation",
        "corners-only",
        "--triangle-subdivision",
        "smooth",
    ];
    assert_eq!(
        output_of(&old, "old_refine.obj"),
        output_of(&new, "new_refine.obj")
    );
}

/// The table's values of the row whose Python keyword (else CLI flag) is `option`.
fn values_of(rows: &[Row], option: &str) -> Vec<String> {
    let flag = format!("--{}", option.replace('_', "-"));
    let row = rows
        .iter()
        .find(|r| r.python_keyword.iter().any(|k| k == option))
        .or_else(|| rows.iter().find(|r| r.cli_flag.as_deref() == Some(&flag)))
        .unwrap_or_else(|| panic!("{option}: not in docs/vocabulary.md"));
    row.values.clone()
}

fn check<T: OptionValue + std::fmt::Display + std::str::FromStr>(rows: &[Row]) {
    let names: Vec<String> = T::names().map(str::to_string).collect();
    assert_eq!(values_of(rows, T::OPTION), names, "{}", T::OPTION);
    for &v in T::ALL {
        assert_eq!(v.to_string().parse::<T>().ok(), Some(v));
    }
}

#[test]
fn library_names_match_the_table() {
    let rows = table();
    check::<subsurf::Scheme>(&rows);
    check::<subsurf::BoundaryInterpolation>(&rows);
    check::<subsurf::CreaseMethod>(&rows);
    check::<subsurf::TriangleSubdivision>(&rows);
    check::<subsurf::FVarLinearInterpolation>(&rows);
    check::<subsurf::surface::MethodName>(&rows);
    check::<subsurf::surface::BackendName>(&rows);
    check::<subsurf::surface::Colors>(&rows);
    check::<subsurf_render::View>(&rows);
    check::<subsurf_render::UpAxis>(&rows);
    check::<subsurf_render::Fit>(&rows);
}
