//! `archive.csv`: a MAP-Elites run's archive after its latest generation, one line per
//! filled cell, replaced atomically after every generation (a killed run leaves the previous
//! whole file; a resumed run rewrites it after its first generation).
//!
//! # Format
//!
//! UTF-8, `\n` line ends, nothing quoted. The header names, for descriptors `a`, `b`:
//! `cell_a,cell_b,a,b,fitness,generation,individual`: each dimension's bin index (from 0),
//! each descriptor's measure (unscaled), the elite's fitness, and its genome id (the
//! generation it was evaluated in and its index there, as `extract --individual` and
//! champions.jsonl name individuals). Lines in cell order (the last dimension fastest).
//! Floats as fitness.csv writes them (`ryu`'s shortest round-trip text).
//!
//! `berry-evolve plot` draws the file as a heat map: [`crate::view::heat_map`].

use super::atomic::write_atomic;
use super::fitness_csv::float_text;
use crate::evo::search::grid::ArchiveView;
use std::io;
use std::path::Path;

/// The file's name in a run folder.
pub const ARCHIVE_FILE: &str = "archive.csv";

/// The header line of `archive`'s file, without its `\n`.
pub fn header(archive: &ArchiveView<'_>) -> String {
    let mut columns: Vec<String> = archive
        .dimensions
        .iter()
        .map(|d| format!("cell_{}", d.measure))
        .collect();
    columns.extend(archive.dimensions.iter().map(|d| d.measure.clone()));
    columns.extend(["fitness", "generation", "individual"].map(String::from));
    columns.join(",")
}

/// `archive` as the bytes of archive.csv.
pub fn to_bytes(archive: &ArchiveView<'_>) -> Vec<u8> {
    let mut text = header(archive);
    text.push('\n');
    for e in &archive.elites {
        let mut fields: Vec<String> = e.cell.iter().map(usize::to_string).collect();
        fields.extend(e.measures.iter().map(|&m| float_text(m)));
        fields.push(float_text(e.fitness));
        fields.push(e.id.generation.to_string());
        fields.push(e.id.individual.to_string());
        text.push_str(&fields.join(","));
        text.push('\n');
    }
    text.into_bytes()
}

/// Replaces `dir`'s archive.csv with `archive`, atomically.
pub fn write(dir: &Path, archive: &ArchiveView<'_>) -> io::Result<()> {
    write_atomic(&dir.join(ARCHIVE_FILE), &to_bytes(archive))
}
