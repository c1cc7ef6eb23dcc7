//! Frictional mesh-convergence study (development tool, docs/replication.md R11):
//! `cargo run --release --example friction_probe` with environment variables
//! AR (0.3), TAU (τ_max/E*, 0.1), MESHES (face elements, e.g. "48,64,96,128"), OUT (folder,
//! /tmp/friction_probe), and the knobs the study varies: EC (`elastic_slip_over_element`, 0.005),
//! RTOL and LOOSE (the Newton tolerances, 1e-10 and 1e-5), SEMI (1: the semismooth branch choice,
//! 0: the plain Newton step), EDGE_LS (halvings of the bordered solve's line search, 8), PEAK (the
//! face grading's peak ratio, 4), COARSEN (its `coarsen_at_aspect`, 0), KIN (finite or linear),
//! DA (`StepOptions::da_target`, 0: the next event is the first free node beyond the edge; above 0
//! it skips the nodes closer than that; frictionless only, `StepOptions::da_target_for`), and REF (a folder of an earlier run: each curve is compared with
//! that run's curve of the same mesh, printing the largest relative difference of p̄ over
//! a/λ ∈ [0.05, 0.45], this curve read by `fe::convergence::p_at` at the earlier curve's points).
//!
//! Per mesh it prints the wall time and the Newton iterations, and writes `OUT/mN.csv`, one row per
//! converged point: a/λ, p̄/E*, d/λ, Newton iterations and the face's friction state node by node
//! (`s` stick, `<` slip toward the peak, `>` away from it, from the first face node in contact to
//! the last), and `OUT/nearedgeN.csv`: per point the face nodes about the contact edge (current
//! x and y, contact and stick flags, p/E*, τ/E*, and the height of the element above), from which
//! other edge rules can be evaluated without solving again.
// The face arrays of a state (nodes above, contact, stick, tractions) are read in parallel by face node.
#![allow(clippy::needless_range_loop)]

use std::ops::ControlFlow;
use std::time::Instant;
use wavy::csv_text::CsvTable;
use wavy::fe::{
    convergence::p_at, solve_with_states, CurvePoint, Interface, Kinematics, MeshLevel,
    NewtonOptions, SolveOptions, StepState,
};

fn env(name: &str, default: &str) -> String {
    std::env::var(name).unwrap_or_else(|_| default.to_string())
}

fn number(name: &str, default: &str) -> f64 {
    let text = env(name, default);
    text.parse()
        .unwrap_or_else(|_| panic!("{name} = `{text}` is not a number"))
}

/// Face nodes written before and after the last node in contact.
const NEAR_EDGE: (usize, usize) = (8, 4);

/// The face's friction state, one character per node in contact (module documentation).
fn friction_pattern(state: &StepState) -> String {
    let d = &state.deformed;
    (1..d.bottom.len())
        .filter(|&k| d.in_contact[k])
        .map(|k| match (d.in_stick[k], d.contact_shear_over_estar[k]) {
            (true, _) => 's',
            (false, t) if t > 0.0 => '>',
            _ => '<',
        })
        .collect()
}

/// Per face node, the node above it in the reference mesh (the top of its element's edge).
fn nodes_above(state: &StepState) -> Vec<usize> {
    let r = &state.reference_nodes;
    state
        .deformed
        .bottom
        .iter()
        .map(|&n| {
            (0..r.len())
                .filter(|&m| r[m][0] == r[n][0] && r[m][1] > r[n][1])
                .min_by(|&a, &b| r[a][1].total_cmp(&r[b][1]))
                .expect("a node above every face node")
        })
        .collect()
}

/// The largest relative difference of `p̄` between `curve` and the curve of an earlier run in
/// `file` (its a/λ and p̄/E* columns) over a/λ ∈ [0.05, 0.45], `curve` read at the earlier
/// points, and the a/λ where it lies.
fn largest_difference(curve: &[CurvePoint], file: &str) -> (f64, f64) {
    let text = std::fs::read_to_string(file).unwrap_or_else(|e| panic!("REF: {file}: {e}"));
    let table = CsvTable::parse(&text).unwrap_or_else(|e| panic!("REF: {file}: {e}"));
    let number = |row: usize, name: &str| -> f64 {
        let cell = table.cell(row, name);
        cell.and_then(|c| c.parse().ok())
            .unwrap_or_else(|| panic!("REF: {file}: row {row} has no {name}"))
    };
    let mut largest = (0.0, f64::NAN);
    for row in 0..table.rows.len() {
        let (a, p) = (number(row, "a_over_lambda"), number(row, "p_over_estar"));
        if !(0.05..=0.45).contains(&a) {
            continue;
        }
        if let Some(q) = p_at(curve, a) {
            let difference = (q / p - 1.0).abs();
            if difference > largest.0 {
                largest = (difference, a);
            }
        }
    }
    largest
}

fn main() {
    let tau = number("TAU", "0.1");
    let out = env("OUT", "/tmp/friction_probe");
    std::fs::create_dir_all(&out).expect("output folder");
    let mut problem = wavy::defaults::layer_problem(number("AR", "0.3"));
    problem.interface = Interface::coulomb_orowan(1.0, tau, number("EC", "0.005"));
    if env("KIN", "finite") == "linear" {
        problem.kinematics = Kinematics::Linear;
    }
    let mut opts = SolveOptions {
        newton: NewtonOptions {
            residual_rtol: number("RTOL", "1e-10"),
            loose_residual_rtol: number("LOOSE", "1e-5"),
            semismooth_friction: env("SEMI", "1") == "1",
            max_edge_line_search: number("EDGE_LS", "8") as usize,
            max_active_set_updates: number("AS_UPDATES", "40") as usize,
            ..NewtonOptions::default()
        },
        ..SolveOptions::default()
    };
    opts.grading.peak_ratio = number("PEAK", "4");
    opts.grading.coarsen_at_aspect = number("COARSEN", "0");
    opts.steps.da_target = number("DA", "0");
    for m in env("MESHES", "48").split(',') {
        let nx: usize = m.trim().parse().expect("MESHES: face element counts");
        let opts = SolveOptions {
            mesh: MeshLevel::Elements { nx, ny: nx / 2 },
            ..opts
        };
        let started = Instant::now();
        let mut rows = vec![
            "a_over_lambda,p_over_estar,slab_displacement_over_lambda,newton_iterations,friction"
                .to_string(),
        ];
        let mut near = vec![
            "point,k,x,y,in_contact,in_stick,pressure_over_estar,shear_over_estar,element_height"
                .to_string(),
        ];
        let mut above = Vec::new();
        let result = solve_with_states(&problem, &opts, false, &mut |_, p, state| {
            if above.is_empty() {
                above = nodes_above(state);
            }
            rows.push(format!(
                "{},{},{},{},{}",
                p.a_over_lambda,
                p.p_over_estar,
                p.slab_displacement_over_lambda,
                p.newton_iterations,
                friction_pattern(state)
            ));
            let d = &state.deformed;
            let point = rows.len() - 2;
            let last = (0..d.bottom.len())
                .rev()
                .find(|&k| d.in_contact[k])
                .unwrap_or(0);
            for k in last.saturating_sub(NEAR_EDGE.0)..(last + NEAR_EDGE.1).min(d.bottom.len()) {
                let n = d.bottom[k];
                near.push(format!(
                    "{point},{k},{},{},{},{},{},{},{}",
                    d.nodes[n][0],
                    d.nodes[n][1],
                    u8::from(d.in_contact[k]),
                    u8::from(d.in_stick[k]),
                    d.contact_pressure_over_estar[k],
                    d.contact_shear_over_estar[k],
                    d.nodes[above[k]][1] - d.nodes[n][1]
                ));
            }
            ControlFlow::Continue(())
        });
        let curve = result.unwrap_or_else(|f| panic!("mesh {nx}: {}", f.error));
        let iterations: usize = curve.points.iter().map(|p| p.newton_iterations).sum();
        println!(
            "mesh {nx}: {:.1} s, {} points, {iterations} Newton iterations ({:.2} per point)",
            started.elapsed().as_secs_f64(),
            curve.points.len(),
            iterations as f64 / curve.points.len() as f64
        );
        if let Ok(reference) = std::env::var("REF") {
            let (difference, at) =
                largest_difference(&curve.points, &format!("{reference}/m{nx}.csv"));
            println!(
                "mesh {nx}: p̄ differs from {reference}'s by at most {difference:.2e} (a/λ {at:.4})"
            );
        }
        std::fs::write(format!("{out}/m{nx}.csv"), rows.join("\n") + "\n").expect("write");
        std::fs::write(format!("{out}/nearedge{nx}.csv"), near.join("\n") + "\n").expect("write");
    }
}
