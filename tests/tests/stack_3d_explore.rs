use meterstick_core::scene::spatial::{Stack3d2, Stack3d3, Stack3dParams};
#[test]
fn explore() {
    for (b, s, deg) in [(2, 0.98, 0.0), (2, 1.02, 0.0), (2, 0.98, 30.0), (2, 1.02, 30.0), (3, 0.98, 0.0), (3, 1.02, 45.0)] {
        let p = Stack3dParams::<f64> { overhang: s, heading: f64::to_radians(deg), max_time: 1.0, ..Default::default() };
        let (mut steps, mut pivots, mut tries, mut maxc) = (0u32, 0u64, 0u32, 0usize);
        let t0 = std::time::Instant::now();
        let outcome = if b == 2 {
            let mut sc = Stack3d2::<f64>::new(p).unwrap();
            while let Some(r) = sc.step() { steps += 1; pivots += r.pivots as u64; tries = tries.max(r.contacts.iter().map(|c| c.directions).max().unwrap()); maxc = maxc.max(r.points.iter().filter(|p| p.is_some()).count()); }
            sc.outcome()
        } else {
            let mut sc = Stack3d3::<f64>::new(p).unwrap();
            while let Some(r) = sc.step() { steps += 1; pivots += r.pivots as u64; tries = tries.max(r.contacts.iter().map(|c| c.directions).max().unwrap()); maxc = maxc.max(r.points.iter().filter(|p| p.is_some()).count());}
            sc.outcome()
        };
        println!("B={b} s={s} psi={deg}: {outcome:?} steps={steps} pivots={pivots} maxtries={tries} maxcontacts={maxc} {:?}/step", t0.elapsed() / steps.max(1));
    }
}
