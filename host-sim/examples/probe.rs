use meterstick_core::scene::*;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let v: f64 = args.get(1).map_or(0.1, |s| s.parse().unwrap());
    let x1: f64 = args.get(2).map_or(-0.35, |s| s.parse().unwrap());
    let mut p = SceneParams::<f64>::paper();
    p.finger_speed = v;
    p.finger1_x = x1;
    let mut s = Scene::<f64, 8, 256>::new(p).unwrap();
    let out = s.run(|_| {});
    println!("outcome {:?} t={} meeting {:?} stats {:?}", out, s.time(), s.meeting(), s.stats());
    for e in s.events() {
        println!(
            "{:.4} f{} {:10} a=({:+.5},{:+.5})",
            e.time,
            e.finger,
            e.mode.name(),
            e.along[0],
            e.along[1]
        );
    }
    let mut s6 = Scene::<f32, 6, 256>::new(SceneParams {
        finger_speed: v as f32,
        finger1_x: x1 as f32,
        ..SceneParams::paper()
    })
    .unwrap();
    let mut first_fire = None;
    let out6 = s6.run(|r| {
        if r.reduced_check_failed && first_fire.is_none() {
            first_fire = Some((r.time, r.state.theta, r.modes));
        }
    });
    println!("first 6x6 firing {:?}", first_fire);
    println!(
        "f32 6x6: outcome {:?} meeting {:?} stats {:?} events {}",
        out6,
        s6.meeting(),
        s6.stats(),
        s6.events().len()
    );
}
#[allow(dead_code)]
fn unused() {}
