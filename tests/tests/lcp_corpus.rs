//! Every file of the Siconos LCP corpus (vendored in `tests/data/lcp-corpus`), read by
//! host-sim's reader and solved by the core solver in f64 and f32, checked against the
//! expectations computed in exact arithmetic (`siconos_parsed.json`): the same matrix, a
//! verified solution that is one of the enumerated complementary solutions, the same pivot
//! count as exact lexicographic Lemke, or the ray error where exact Lemke ends in a ray.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use meterstick_host_sim::lcp_io::{self, Precision};
use meterstick_tests::corpus_dir;
use meterstick_tests::enumeration::{all_solutions, is_lcp_solution};
use serde_json::Value;

fn expectations() -> Vec<Value> {
    let text = std::fs::read_to_string(corpus_dir().join("siconos_parsed.json")).unwrap();
    serde_json::from_str::<Value>(&text).unwrap().as_array().unwrap().clone()
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect()
}

#[test]
fn corpus_files_parse_to_the_expected_matrices() {
    let entries = expectations();
    assert_eq!(entries.len(), 18);
    for e in &entries {
        let file = e["file"].as_str().unwrap();
        let data = lcp_io::parse(&std::fs::read_to_string(corpus_dir().join(file)).unwrap()).unwrap();
        let m: Vec<Vec<f64>> = e["M_row_major"].as_array().unwrap().iter().map(floats).collect();
        assert_eq!(data.m, m, "{file}: M");
        assert_eq!(data.q, floats(&e["q"]), "{file}: q");
    }
}

#[test]
fn corpus_solves_as_exact_lexicographic_lemke_does() {
    let mut table = Vec::new();
    for e in expectations() {
        let file = e["file"].as_str().unwrap();
        let data = lcp_io::parse(&std::fs::read_to_string(corpus_dir().join(file)).unwrap()).unwrap();
        let exact = &e["exact_lex_lemke"];
        let solutions: Vec<Vec<f64>> =
            e["basic_solutions_float"].as_array().unwrap().iter().map(floats).collect();
        // The test's own enumeration agrees with the exact one on the number of solutions.
        assert_eq!(all_solutions(&data.m, &data.q).len(), solutions.len(), "{file}: enumeration");
        for precision in [Precision::F64, Precision::F32] {
            let report = lcp_io::solve(&data, precision).unwrap();
            table.push(format!("{file} {precision:?}: {} after {} pivots", report.status, report.pivots));
            match exact["result"].as_str().unwrap() {
                "solution" => {
                    assert_eq!(report.status, "solution", "{file} {precision:?}");
                    let z = report.z.unwrap();
                    let tol = if precision == Precision::F64 { 1e-12 } else { 1e-5 };
                    assert!(is_lcp_solution(&data.m, &data.q, &z, tol), "{file} {precision:?}: {z:?}");
                    let close = |s: &Vec<f64>| {
                        s.iter().zip(&z).all(|(a, b)| (a - b).abs() <= 1e3 * tol * (1.0 + a.abs()))
                    };
                    assert!(
                        solutions.iter().any(close),
                        "{file} {precision:?}: z {z:?} not among {solutions:?}"
                    );
                    if precision == Precision::F64 {
                        assert_eq!(
                            u64::from(report.pivots),
                            exact["pivots"].as_u64().unwrap(),
                            "{file}: pivots vs exact Lemke"
                        );
                    }
                }
                "ray" => assert_eq!(report.status, "ray", "{file} {precision:?}"),
                other => panic!("{file}: unexpected exact result {other}"),
            }
        }
    }
    println!("{}", table.join("\n"));
}
