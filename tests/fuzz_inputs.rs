//! Seeded mutation fuzzing of the two readers of user files: the gmsh mesh reader (with the
//! validation and the degree conversions that follow it) and the scene parser. Every mutated input
//! must give `Ok` or an `Err`, never a panic. Inputs: the committed meshes (ASCII) and their
//! binary twin, and the example scenes. The default run makes 20 000 inputs (under a minute in a
//! release build); `RINGCONTACT_FUZZ_CASES=N` runs more (the nightly script uses 200 000).

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::PathBuf;

use ringcontact::discretisation::assembly::assemble_stiffness;
use ringcontact::discretisation::element::Lame;
use ringcontact::discretisation::quadrature::TriangleRule;
use ringcontact::fem::contact::ContactModel;
use ringcontact::mesh::msh::parse_msh;
use ringcontact::mesh::triangulation::{tags, Degree};
use ringcontact::scene::SceneSpec;
use ringcontact::sparse::constrained::ConstrainedCholesky;

/// xorshift64*: deterministic, no dependency.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// Replacement tokens that stress parsers: huge counts, signs, non-finite values, tags.
const TOKENS: &[&str] = &[
    "0",
    "-1",
    "1",
    "2",
    "4",
    "1152921504606846976",
    "18446744073709551615",
    "1000000000000",
    "2147483648",
    "-2147483649",
    "1e308",
    "-1e308",
    "1e-310",
    "nan",
    "inf",
    "-inf",
    "0.5",
    "9",
    "$EndNodes",
    "$Nodes",
    "$EndElements",
    "",
    "\"",
    "[",
    "=",
    "true",
];

/// Byte range of the line holding position `at`, its newline included.
fn line_around(text: &[u8], at: usize) -> (usize, usize) {
    let start = text[..at]
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |p| p + 1);
    let end = text[at..]
        .iter()
        .position(|&b| b == b'\n')
        .map_or(text.len(), |p| at + p + 1);
    (start, end)
}

fn mutate(rng: &mut Rng, input: &[u8]) -> Vec<u8> {
    let mut out = input.to_vec();
    let edits = 1 + rng.below(4);
    for _ in 0..edits {
        if out.is_empty() {
            out.push(b'0');
        }
        let at = rng.below(out.len());
        match rng.below(10) {
            // Replace a token of a section's count line (the line after `$Nodes`, `$Elements`,
            // ...): the counts a reader may trust for allocations.
            8 | 9 => {
                let headers: Vec<usize> = out
                    .windows(2)
                    .enumerate()
                    .filter(|(_, w)| w[0] == b'\n' && w[1] == b'$')
                    .filter_map(|(i, _)| {
                        out[i + 1..]
                            .iter()
                            .position(|&b| b == b'\n')
                            .map(|p| i + 2 + p)
                    })
                    .filter(|&line| line < out.len())
                    .collect();
                if headers.is_empty() {
                    continue;
                }
                let start = headers[rng.below(headers.len())];
                let end = out[start..]
                    .iter()
                    .position(|&b| b == b'\n')
                    .map_or(out.len(), |p| start + p);
                let mut words: Vec<Vec<u8>> = out[start..end]
                    .split(|b| *b == b' ')
                    .map(|w| w.to_vec())
                    .collect();
                let k = rng.below(words.len());
                words[k] = TOKENS[rng.below(TOKENS.len())].as_bytes().to_vec();
                let line = words.join(&b' ');
                out.splice(start..end, line);
            }
            // Flip a byte.
            0 => out[at] ^= 1 << rng.below(8),
            // Replace the number (or word) at `at` with a hostile token.
            1 | 2 => {
                let start = out[..at]
                    .iter()
                    .rposition(|b| b.is_ascii_whitespace())
                    .map_or(0, |p| p + 1);
                let end = out[at..]
                    .iter()
                    .position(|b| b.is_ascii_whitespace())
                    .map_or(out.len(), |p| at + p);
                let token = TOKENS[rng.below(TOKENS.len())].as_bytes();
                out.splice(start..end, token.iter().copied());
            }
            // Truncate.
            3 => out.truncate(at),
            // Delete a line.
            4 => {
                let (start, end) = line_around(&out, at);
                out.drain(start..end);
            }
            // Duplicate a line.
            5 => {
                let (start, end) = line_around(&out, at);
                let line = out[start..end].to_vec();
                out.splice(end..end, line);
            }
            // Insert a random byte.
            6 => out.insert(at, rng.next() as u8),
            // Swap a digit for another.
            _ => {
                if out[at].is_ascii_digit() {
                    out[at] = b'0' + rng.below(10) as u8;
                }
            }
        }
    }
    out
}

fn cases() -> usize {
    std::env::var("RINGCONTACT_FUZZ_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(20_000)
}

fn meshes() -> Vec<(String, Vec<u8>)> {
    let dir = ringcontact::fem::solver::mesh_directory();
    let mut out = Vec::new();
    for name in [
        "small-domain-R5.msh",
        "small-domain-R5-binary.msh",
        "annulus-0.9-L0.msh",
    ] {
        let path: PathBuf = dir.join(name);
        out.push((name.to_string(), std::fs::read(&path).unwrap()));
    }
    out
}

/// Read, validate and raise the degree as the solver does, then assemble and solve the flat
/// punch on what is accepted (a mutated mesh that passes every check must still not crash the
/// solver).
fn read_like_the_solver(bytes: &[u8]) -> Result<usize, String> {
    let mesh = parse_msh(bytes, "fuzzed.msh").map_err(|e| e.to_string())?;
    mesh.validate(&[
        (tags::CONTACT, "contact"),
        (tags::FAR, "far"),
        (tags::AXIS, "axis"),
    ])
    .map_err(|e| e.to_string())?;
    let start = mesh
        .boundary_nodes(tags::CONTACT)
        .iter()
        .map(|&n| mesh.nodes[n][0])
        .fold(f64::INFINITY, f64::min);
    mesh.validate_geometry(start).map_err(|e| e.to_string())?;
    let cubic = mesh.with_degree(Degree::Cubic);
    let quadratic = mesh.with_degree(Degree::Quadratic);
    let k = assemble_stiffness(
        &quadratic,
        &Lame::from_young_poisson(1.0, 0.0),
        &TriangleRule::degree4(),
    )
    .map_err(|e| e.to_string())?;
    let mut solver = ConstrainedCholesky::new(&k).map_err(|e| e.to_string())?;
    let model = ContactModel::new(&quadratic, k.nrows()).map_err(|e| e.to_string())?;
    let flat = model.flat(&mut solver, 1.0).map_err(|e| e.to_string())?;
    if !flat.force.is_finite() {
        return Err("non-finite force".into());
    }
    Ok(cubic.nodes.len())
}

#[test]
fn mutated_meshes_never_panic() {
    let inputs = meshes();
    for (name, bytes) in &inputs {
        assert!(
            read_like_the_solver(bytes).is_ok(),
            "{name} itself must read"
        );
    }
    let mut rng = Rng(0x5eed_1234_abcd_0001);
    let (mut accepted, mut rejected) = (0, 0);
    let total = cases() * 3 / 4;
    for case in 0..total {
        let (name, bytes) = &inputs[case % inputs.len()];
        let mutated = mutate(&mut rng, bytes);
        match catch_unwind(AssertUnwindSafe(|| read_like_the_solver(&mutated))) {
            Ok(Ok(_)) => accepted += 1,
            Ok(Err(_)) => rejected += 1,
            Err(_) => {
                let path = std::env::temp_dir().join(format!("ringcontact-fuzz-panic-{case}.msh"));
                let _ = std::fs::write(&path, &mutated);
                panic!(
                    "case {case} (from {name}) panicked; input saved to {}",
                    path.display()
                );
            }
        }
    }
    println!("{total} mutated meshes: {accepted} accepted, {rejected} rejected, 0 panics");
}

#[test]
fn mutated_scenes_never_panic() {
    let dir = ringcontact::mesh::files::DataPaths::default()
        .root
        .join("verify/scenes");
    let mut inputs = Vec::new();
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            inputs.push(std::fs::read(&path).unwrap());
        }
    }
    assert!(!inputs.is_empty());
    let mut rng = Rng(0x5eed_1234_abcd_0002);
    let (mut accepted, mut rejected) = (0, 0);
    let total = cases() / 4;
    for case in 0..total {
        let mutated = mutate(&mut rng, &inputs[case % inputs.len()]);
        let text = String::from_utf8_lossy(&mutated).into_owned();
        let outcome = catch_unwind(AssertUnwindSafe(|| {
            SceneSpec::from_toml(&text, "fuzzed.toml").and_then(|s| s.validate())
        }));
        match outcome {
            Ok(Ok(_)) => accepted += 1,
            Ok(Err(_)) => rejected += 1,
            Err(_) => panic!("scene case {case} panicked on:\n{text}"),
        }
    }
    println!("{total} mutated scenes: {accepted} accepted, {rejected} rejected, 0 panics");
}
