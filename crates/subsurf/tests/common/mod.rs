//! Shared test helpers: the regression shapes in `testdata/shapes` and their `index.tsv`.
#![allow(dead_code)]

use std::collections::HashMap;
use std::path::PathBuf;

/// `testdata/shapes` at the repository root.
pub fn shapes_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../testdata/shapes")
}

/// One row of `index.tsv`, keyed by column name.
#[derive(Debug, Clone)]
pub struct Row(pub HashMap<String, String>);

impl Row {
    pub fn get(&self, col: &str) -> &str {
        self.0
            .get(col)
            .unwrap_or_else(|| panic!("index.tsv has no column {col}"))
    }
    pub fn usize(&self, col: &str) -> usize {
        self.get(col)
            .parse()
            .unwrap_or_else(|_| panic!("column {col} is not a number: {}", self.get(col)))
    }
}

/// All rows of `index.tsv`.
pub fn index() -> Vec<Row> {
    let text = std::fs::read_to_string(shapes_dir().join("index.tsv")).expect("index.tsv");
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().expect("header").split('\t').collect();
    lines
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let cells: Vec<&str> = l.split('\t').collect();
            assert_eq!(cells.len(), header.len(), "index.tsv row: {l}");
            Row(header
                .iter()
                .zip(cells)
                .map(|(h, c)| (h.to_string(), c.to_string()))
                .collect())
        })
        .collect()
}

/// Path of a shape by name.
pub fn shape_path(name: &str) -> PathBuf {
    shapes_dir().join(format!("{name}.obj"))
}
