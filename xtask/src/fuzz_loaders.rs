//! `cargo xtask fuzz --loaders`: mutation fuzzing of the OBJ, MTL, glTF and GLB loaders.
//!
//! Each case takes a seed file (test_support::loaders::loader_seeds) and applies 1 to 5
//! mutations drawn by proptest: raw ones (bit flips, byte writes, inserted format tokens,
//! deleted and duplicated ranges, extreme numbers) or, for glTF and GLB, structured ones
//! (one JSON value replaced, removed or duplicated; GLB chunks reassembled). The input must pass test_support's one check (no panic; a valid
//! mesh or a typed error) within a time bound. A failing input is shrunk by proptest (fewer
//! and simpler mutations), then line by line, and saved under `tests/data/loaders/`, where
//! `cargo test` replays it.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::{Duration, Instant};

use anyhow::{Context, Result};
use proptest::prelude::*;
use proptest::sample::Index;
use proptest::strategy::ValueTree;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use test_support::loaders::{
    LoaderFormat, Verdict, check_loader_input, loader_cases_dir, loader_seeds,
};

use crate::progress;

/// One input taking longer than this (all option sets together) counts as a failure:
/// loading must be bounded in time.
const SLOW: Duration = Duration::from_secs(2);

/// Tokens worth inserting, per format: keywords, separators, extreme numbers, paths that
/// leave the folder.
fn tokens(format: LoaderFormat) -> &'static [&'static [u8]] {
    match format {
        LoaderFormat::Obj => &[
            b"\nv ",
            b"\nf ",
            b"\nvt ",
            b"\nvn ",
            b"\nl ",
            b"\no x",
            b"\ng ",
            b"\nusemtl ",
            b"\nmtllib ../x.mtl",
            b" ",
            b"/",
            b"//",
            b"\n",
            b"#",
            b"\\\n",
            b"\r",
            b"\0",
            b"0",
            b"-1",
            b"1e308",
            b"-1e308",
            b"1e-320",
            b"nan",
            b"inf",
            b"4294967295",
            b"-9223372036854775808",
            b"18446744073709551616",
            b" 1 2 3 4",
        ],
        LoaderFormat::Mtl => &[
            b"\nnewmtl ",
            b"\nKd ",
            b"\nKa ",
            b"\nKs ",
            b"\nd ",
            b"\nTr ",
            b"\nmap_Kd ",
            b"../",
            b"/etc/passwd",
            b"-s 1 1 1 ",
            b"\n",
            b" ",
            b"#",
            b"\0",
            b"0",
            b"-1",
            b"nan",
            b"inf",
            b"1e308",
        ],
        LoaderFormat::Gltf | LoaderFormat::Glb => &[
            b"\"",
            b"{",
            b"}",
            b"[",
            b"]",
            b",",
            b":",
            b"null",
            b"true",
            b"-1",
            b"0",
            b"4294967295",
            b"18446744073709551616",
            b"1e400",
            b"\"children\": [0],",
            b"\"uri\": \"../x.bin\",",
            b"\"uri\": \"/etc/passwd\",",
            b"\"byteLength\": 99999999999,",
            b"\"count\": 4294967295,",
            b"\"mode\": 1,",
            b"data:application/octet-stream;base64,",
            b"%FF",
            b"%2E%2E/",
            b"\"byteStride\": 4,",
            b"\"sparse\": {\"count\": 1},",
            b"\"scene\": 7,",
            b"\"matrix\": [1e400],",
            b"\"componentType\": 5121,",
            b"\"type\": \"SCALAR\",",
        ],
        LoaderFormat::Png => &[
            b"IHDR",
            b"IDAT",
            b"PLTE",
            b"tRNS",
            b"IEND",
            b"acTL",
            b"fcTL",
            b"\xff\xff\xff\xff",
            b"\x7f\xff\xff\xff",
            b"\0\0\0\0",
            b"\x00\x01\x00\x00",
            b"\x10",
            b"\x03",
            b"\x01",
        ],
        LoaderFormat::Jpeg => &[
            b"\xff\xc0",
            b"\xff\xc2",
            b"\xff\xc4",
            b"\xff\xda",
            b"\xff\xd9",
            b"\xff\xdb",
            b"\xff\xdd",
            b"\xff\xd0",
            b"\xff\xff",
            b"\xff\x00",
            b"\x00\x00",
            b"\xff\xe1",
        ],
    }
}

/// One mutation of a byte string.
#[derive(Clone, Debug)]
enum Mutation {
    /// Flip one bit.
    Flip(Index, u8),
    /// Overwrite one byte.
    Set(Index, u8),
    /// Insert a token of the format.
    Insert(Index, Index),
    /// Delete up to `len` bytes.
    Delete(Index, u16),
    /// Duplicate up to `len` bytes in place.
    Duplicate(Index, u16),
    /// Replace one number written in the text with an extreme one (keeps JSON valid).
    Number(Index, Index),
    /// glTF: parse the JSON, change one value (by its pre-order position), write it back.
    Json(Index, JsonEdit),
    /// PNG: recompute every chunk's CRC (as far as the chunk structure holds).
    FixCrcs,
}

/// Recomputes the CRC of every PNG chunk whose length fits the bytes.
fn fix_png_crcs(bytes: &mut [u8]) {
    fn crc32(data: &[u8]) -> u32 {
        let mut crc = 0xFFFF_FFFFu32;
        for &b in data {
            crc ^= u32::from(b);
            for _ in 0..8 {
                crc = if crc & 1 == 1 {
                    (crc >> 1) ^ 0xEDB8_8320
                } else {
                    crc >> 1
                };
            }
        }
        !crc
    }
    let mut at = 8;
    while at + 12 <= bytes.len() {
        let len = u32::from_be_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]);
        let Some(end) = (at + 8).checked_add(len as usize) else {
            return;
        };
        if end + 4 > bytes.len() {
            return;
        }
        let crc = crc32(&bytes[at + 4..end]);
        bytes[end..end + 4].copy_from_slice(&crc.to_be_bytes());
        at = end + 4;
    }
}

/// One edit of a JSON value.
#[derive(Clone, Debug)]
enum JsonEdit {
    /// Replace it with a number from [`NUMBERS`].
    Number(Index),
    /// Replace it with a string from [`STRINGS`].
    String(Index),
    /// Remove it from its object or array.
    Remove,
    /// Duplicate it (array element) or copy it over a sibling key (object member).
    Duplicate,
    /// Replace it with `null`, `[]` or `{}`.
    Empty(u8),
}

/// Strings worth putting in a glTF document: URIs that leave the folder, bad encodings,
/// enum names.
const STRINGS: &[&str] = &[
    "../x.bin",
    "/etc/passwd",
    "file:///etc/passwd",
    "%2E%2E/%2E%2E/x.bin",
    "%FF",
    "Box0.bin",
    "data:application/octet-stream;base64,AAAA",
    "data:application/octet-stream;base64,!!!!",
    "data:,raw",
    "http://example.com/x.bin",
    "SCALAR",
    "VEC2",
    "MAT4",
    "POSITION",
    "",
];

/// Numbers that stress parsers and size checks.
const NUMBERS: &[&str] = &[
    "0",
    "1",
    "-1",
    "2",
    "3",
    "4",
    "5",
    "7",
    "255",
    "65535",
    "4294967295",
    "4294967296",
    "18446744073709551615",
    "9223372036854775807",
    "-2147483648",
    "1e308",
    "-1e308",
    "1e400",
    "1e-320",
    "0.5",
    "-0",
    "99999999",
];

/// Byte ranges of the numbers written in `bytes` (digit runs with sign, point, exponent).
fn number_spans(bytes: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i].is_ascii_digit() {
            let mut start = i;
            if start > 0 && bytes[start - 1] == b'-' {
                start -= 1;
            }
            while i < bytes.len()
                && (bytes[i].is_ascii_digit()
                    || matches!(bytes[i], b'.' | b'e' | b'E' | b'+' | b'-'))
            {
                i += 1;
            }
            spans.push((start, i));
        } else {
            i += 1;
        }
    }
    spans
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        1 => (any::<Index>(), 0u8..8).prop_map(|(at, bit)| Mutation::Flip(at, bit)),
        1 => (any::<Index>(), any::<u8>()).prop_map(|(at, b)| Mutation::Set(at, b)),
        3 => (any::<Index>(), any::<Index>()).prop_map(|(at, t)| Mutation::Insert(at, t)),
        1 => (any::<Index>(), 1u16..512).prop_map(|(at, n)| Mutation::Delete(at, n)),
        1 => (any::<Index>(), 1u16..4096).prop_map(|(at, n)| Mutation::Duplicate(at, n)),
        4 => (any::<Index>(), any::<Index>()).prop_map(|(at, n)| Mutation::Number(at, n)),
    ]
}

/// The mutations of one case. glTF and GLB cases are structured (JSON edits that keep
/// the document parseable, so the loader's deeper checks are reached) two times in three,
/// raw bytes otherwise.
fn mutations(format: LoaderFormat) -> BoxedStrategy<Vec<Mutation>> {
    let raw = prop::collection::vec(mutation(), 1..6);
    match format {
        LoaderFormat::Obj | LoaderFormat::Mtl | LoaderFormat::Jpeg => raw.boxed(),
        // PNG: chunk CRCs are fixed after mutating two times in three (else the decoder
        // stops at the first CRC).
        LoaderFormat::Png => prop_oneof![
            2 => prop::collection::vec(mutation(), 1..6).prop_map(|mut m| {
                m.push(Mutation::FixCrcs);
                m
            }),
            1 => raw,
        ]
        .boxed(),
        LoaderFormat::Gltf | LoaderFormat::Glb => {
            let json = (any::<Index>(), json_edit()).prop_map(|(at, e)| Mutation::Json(at, e));
            prop_oneof![
                2 => prop::collection::vec(json, 1..6),
                1 => raw,
            ]
            .boxed()
        }
    }
}

fn json_edit() -> impl Strategy<Value = JsonEdit> {
    prop_oneof![
        3 => any::<Index>().prop_map(JsonEdit::Number),
        2 => any::<Index>().prop_map(JsonEdit::String),
        2 => Just(JsonEdit::Remove),
        1 => Just(JsonEdit::Duplicate),
        1 => (0u8..3).prop_map(JsonEdit::Empty),
    ]
}

/// Applies one JSON edit to the `target`-th value (pre-order) of `root`.
fn edit_json(root: &mut serde_json::Value, target: &Index, edit: &JsonEdit) {
    use serde_json::Value;
    fn count(v: &Value) -> usize {
        1 + match v {
            Value::Array(a) => a.iter().map(count).sum(),
            Value::Object(o) => o.values().map(count).sum(),
            _ => 0,
        }
    }
    /// Walks to the `k`-th descendant of `v` (0 = `v` itself is excluded: the root is
    /// never edited) and edits it in its parent.
    fn walk(v: &mut Value, k: &mut usize, edit: &JsonEdit) -> bool {
        let replacement = |edit: &JsonEdit, old: &Value| -> Option<Value> {
            Some(match edit {
                JsonEdit::Number(n) => {
                    let text = NUMBERS[n.index(NUMBERS.len())];
                    serde_json::from_str(text).unwrap_or(Value::Null)
                }
                JsonEdit::String(n) => Value::String(STRINGS[n.index(STRINGS.len())].into()),
                JsonEdit::Empty(0) => Value::Null,
                JsonEdit::Empty(1) => Value::Array(Vec::new()),
                JsonEdit::Empty(_) => Value::Object(serde_json::Map::new()),
                JsonEdit::Duplicate => old.clone(),
                JsonEdit::Remove => return None,
            })
        };
        match v {
            Value::Array(items) => {
                for i in 0..items.len() {
                    if *k == 0 {
                        match (edit, replacement(edit, &items[i])) {
                            (JsonEdit::Duplicate, Some(copy)) => items.insert(i, copy),
                            (_, Some(new)) => items[i] = new,
                            (_, None) => {
                                items.remove(i);
                            }
                        }
                        return true;
                    }
                    *k -= 1;
                    if walk(&mut items[i], k, edit) {
                        return true;
                    }
                }
                false
            }
            Value::Object(members) => {
                let keys: Vec<String> = members.keys().cloned().collect();
                for (j, key) in keys.iter().enumerate() {
                    if *k == 0 {
                        let old = members[key].clone();
                        match (edit, replacement(edit, &old)) {
                            (JsonEdit::Duplicate, Some(copy)) => {
                                let sibling = &keys[(j + 1) % keys.len()];
                                members.insert(sibling.clone(), copy);
                            }
                            (_, Some(new)) => {
                                members.insert(key.clone(), new);
                            }
                            (_, None) => {
                                members.remove(key);
                            }
                        }
                        return true;
                    }
                    *k -= 1;
                    if let Some(child) = members.get_mut(key)
                        && walk(child, k, edit)
                    {
                        return true;
                    }
                }
                false
            }
            _ => false,
        }
    }
    let total = count(root).saturating_sub(1);
    if total > 0 {
        let mut k = target.index(total);
        walk(root, &mut k, edit);
    }
}

/// Splits a GLB into its JSON text and binary chunk (`None` if it is not a well-formed
/// two-chunk GLB).
fn split_glb(bytes: &[u8]) -> Option<(String, Vec<u8>)> {
    let u32_at = |at: usize| -> Option<usize> {
        let b = bytes.get(at..at + 4)?;
        Some(u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize)
    };
    let json_len = u32_at(12)?;
    let json = std::str::from_utf8(bytes.get(20..20 + json_len)?).ok()?;
    let bin_at = 20 + json_len;
    let bin_len = u32_at(bin_at)?;
    let bin = bytes.get(bin_at + 8..bin_at + 8 + bin_len)?;
    Some((json.trim_end().to_owned(), bin.to_vec()))
}

/// Applies `mutations` to `seed`.
fn apply(format: LoaderFormat, seed: &[u8], mutations: &[Mutation]) -> Vec<u8> {
    let mut bytes = seed.to_vec();
    for m in mutations {
        let at = |i: &Index, bytes: &Vec<u8>| i.index(bytes.len() + 1);
        match m {
            Mutation::Flip(i, bit) if !bytes.is_empty() => {
                let k = i.index(bytes.len());
                bytes[k] ^= 1 << bit;
            }
            Mutation::Set(i, b) if !bytes.is_empty() => {
                let k = i.index(bytes.len());
                bytes[k] = *b;
            }
            Mutation::Insert(i, t) => {
                let k = at(i, &bytes);
                let tokens = tokens(format);
                let token = tokens[t.index(tokens.len())];
                bytes.splice(k..k, token.iter().copied());
            }
            Mutation::Delete(i, n) => {
                let k = at(i, &bytes);
                let end = (k + usize::from(*n)).min(bytes.len());
                bytes.drain(k..end);
            }
            Mutation::Duplicate(i, n) => {
                let k = at(i, &bytes);
                let end = (k + usize::from(*n)).min(bytes.len());
                let copy = bytes[k..end].to_vec();
                bytes.splice(end..end, copy);
            }
            Mutation::Json(i, edit) => {
                // glTF: the JSON text; GLB: its JSON chunk, reassembled with valid lengths.
                let (text, bin) = match format {
                    LoaderFormat::Gltf => (String::from_utf8(bytes.clone()).ok(), None),
                    LoaderFormat::Glb => match split_glb(&bytes) {
                        Some((json, bin)) => (Some(json), Some(bin)),
                        None => (None, None),
                    },
                    _ => (None, None),
                };
                if let Some(mut root) = text.and_then(|t| serde_json::from_str(&t).ok()) {
                    edit_json(&mut root, i, edit);
                    let json = serde_json::to_string(&root).unwrap_or_default();
                    bytes = match bin {
                        Some(bin) => test_support::loaders::glb(&json, &bin),
                        None => json.into_bytes(),
                    };
                }
            }
            Mutation::FixCrcs => fix_png_crcs(&mut bytes),
            Mutation::Number(i, n) => {
                let spans = number_spans(&bytes);
                if !spans.is_empty() {
                    let (start, end) = spans[i.index(spans.len())];
                    let number = NUMBERS[n.index(NUMBERS.len())].as_bytes();
                    bytes.splice(start..end, number.iter().copied());
                }
            }
            _ => {}
        }
    }
    bytes
}

/// Why an input fails: the checker's bug description, or too slow.
fn failure(format: LoaderFormat, bytes: &[u8], scratch: &Path) -> Option<String> {
    let start = Instant::now();
    let result = check_loader_input(format, bytes, scratch);
    let elapsed = start.elapsed();
    match result {
        Err(bug) => Some(bug),
        Ok(_) if elapsed > SLOW => Some(format!(
            "took {:.1} s (limit {} s)",
            elapsed.as_secs_f64(),
            SLOW.as_secs()
        )),
        Ok(_) => None,
    }
}

/// Removes lines (text) or halves (binary) while the input still fails.
fn minimise(format: LoaderFormat, mut bytes: Vec<u8>, scratch: &Path) -> Vec<u8> {
    let mut chunk = bytes.len().div_ceil(2).max(1);
    let mut tries = 0;
    while chunk >= 1 && tries < 2_000 {
        let mut start = 0;
        let mut removed = false;
        while start < bytes.len() && tries < 2_000 {
            tries += 1;
            let end = (start + chunk).min(bytes.len());
            let mut candidate = bytes.clone();
            candidate.drain(start..end);
            if failure(format, &candidate, scratch).is_some() {
                bytes = candidate;
                removed = true;
            } else {
                start = end;
            }
        }
        if chunk == 1 && !removed {
            break;
        }
        if !removed {
            chunk /= 2;
        }
    }
    bytes
}

/// A refusal message without its file name, numbers and quoted text, to count kinds.
fn reason(message: &str) -> String {
    let message = message.split_once(": ").map_or(message, |(_, rest)| rest);
    let mut out = String::new();
    let mut quoted = false;
    for c in message.chars() {
        match c {
            '`' => {
                quoted = !quoted;
                if quoted {
                    out.push_str("`…`");
                }
            }
            _ if quoted => {}
            '0'..='9' => {
                if !out.ends_with('#') {
                    out.push('#');
                }
            }
            _ => out.push(c),
        }
    }
    out.chars().take(90).collect()
}

/// Named seed files of one format.
type Seeds = Vec<(String, Vec<u8>)>;

/// Per-format counts of one run.
#[derive(Default)]
struct Tally {
    cases: u64,
    loaded: u64,
    refused: u64,
    failures: u64,
    slowest: Duration,
}

/// Runs `cases` loader inputs (spread over the four formats) from `seed`; saves shrunk
/// failures under `tests/data/loaders/` (or `out`). Fails when any input fails.
pub fn run(cases: u64, seed: u64, out: Option<PathBuf>) -> Result<ExitCode> {
    let out = out.unwrap_or_else(loader_cases_dir);
    let scratch = crate::target_dir().join("fuzz-loaders-scratch");
    std::fs::create_dir_all(&scratch).with_context(|| scratch.display().to_string())?;
    let mut rng_seed = [0u8; 32];
    rng_seed[..8].copy_from_slice(&seed.to_le_bytes());
    rng_seed[8..16].copy_from_slice(b"loaders!");
    let mut runner = TestRunner::new_with_rng(
        Config::default(),
        TestRng::from_seed(RngAlgorithm::ChaCha, &rng_seed),
    );
    let seeds: Vec<(LoaderFormat, Seeds)> = LoaderFormat::ALL
        .iter()
        .map(|&f| (f, loader_seeds(f)))
        .collect();
    let mut tallies: Vec<Tally> = seeds.iter().map(|_| Tally::default()).collect();
    // Panics are expected to be caught and reported; keep their messages off the terminal.
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let bar = progress::bar(cases, "fuzz loaders");
    let start = Instant::now();
    let mut saved = Vec::new();
    let mut reasons: std::collections::HashMap<(LoaderFormat, String), u64> =
        std::collections::HashMap::new();
    for case in 0..cases {
        bar.inc(1);
        let slot = (case % seeds.len() as u64) as usize;
        let (format, files) = &seeds[slot];
        let strategy = (0..files.len(), mutations(*format));
        let mut tree = strategy
            .new_tree(&mut runner)
            .map_err(|e| anyhow::anyhow!("generating case {case}: {e}"))?;
        let (file, mutations) = tree.current();
        let bytes = apply(*format, &files[file].1, &mutations);
        let tally = &mut tallies[slot];
        tally.cases += 1;
        let t = Instant::now();
        let verdict = check_loader_input(*format, &bytes, &scratch);
        tally.slowest = tally.slowest.max(t.elapsed());
        let bug = match verdict {
            Ok(Verdict::Loaded(_)) if t.elapsed() <= SLOW => {
                tally.loaded += 1;
                continue;
            }
            Ok(Verdict::Refused(message)) if t.elapsed() <= SLOW => {
                tally.refused += 1;
                *reasons.entry((*format, reason(&message))).or_insert(0) += 1;
                continue;
            }
            Ok(_) => format!("took {:.1} s", t.elapsed().as_secs_f64()),
            Err(bug) => bug,
        };
        tally.failures += 1;
        // Shrink: fewer and simpler mutations while it still fails, then bytes.
        let mut best = bytes;
        for _ in 0..1_000 {
            if !tree.simplify() {
                break;
            }
            let (file, mutations) = tree.current();
            let candidate = apply(*format, &files[file].1, &mutations);
            if failure(*format, &candidate, &scratch).is_some() {
                best = candidate;
            } else if !tree.complicate() {
                break;
            }
        }
        let best = minimise(*format, best, &scratch);
        let bug = failure(*format, &best, &scratch).unwrap_or(bug);
        let path = save(&out, *format, &best)?;
        let line = format!(
            "{} case {case} (seed file {}): {bug}; shrunk to {} bytes, saved {}",
            format.extension(),
            files[file].0,
            best.len(),
            path.display()
        );
        bar.suspend(|| println!("{line}"));
        saved.push(path);
    }
    bar.finish_and_clear();
    std::panic::set_hook(hook);
    println!(
        "fuzz --loaders: {cases} cases (seed {seed}) in {:.1} s",
        start.elapsed().as_secs_f64()
    );
    println!(
        "{:<6} {:>8} {:>8} {:>8} {:>8} {:>12}",
        "format", "cases", "loaded", "refused", "failed", "slowest ms"
    );
    for ((format, _), t) in seeds.iter().zip(&tallies) {
        println!(
            "{:<6} {:>8} {:>8} {:>8} {:>8} {:>12.1}",
            format.extension(),
            t.cases,
            t.loaded,
            t.refused,
            t.failures,
            t.slowest.as_secs_f64() * 1e3
        );
    }
    let mut top: Vec<_> = reasons.into_iter().collect();
    top.sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.1.cmp(&b.0.1)));
    println!("most frequent refusals (numbers as #):");
    for ((format, why), n) in top.iter().take(12) {
        println!("{n:>8}  {:<5} {why}", format.extension());
    }
    if saved.is_empty() {
        Ok(ExitCode::SUCCESS)
    } else {
        println!(
            "{} failing input(s) saved under {}; `cargo test -p fuzz-checks --test integration loader_cases` replays them",
            saved.len(),
            out.display()
        );
        Ok(ExitCode::FAILURE)
    }
}

/// Saves a failing input as `fuzz-<hash>.<ext>` (content-addressed: a rerun does not
/// duplicate it).
fn save(dir: &Path, format: LoaderFormat, bytes: &[u8]) -> Result<PathBuf> {
    std::fs::create_dir_all(dir).with_context(|| dir.display().to_string())?;
    // FNV-1a: a stable name from the content.
    let hash = bytes.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    });
    let path = dir.join(format!("fuzz-{hash:016x}.{}", format.extension()));
    std::fs::write(&path, bytes).with_context(|| path.display().to_string())?;
    Ok(path)
}
