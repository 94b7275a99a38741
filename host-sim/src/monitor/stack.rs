//! The stack over the link (`SceneId::Stack`, protocol version 7): its parameters read back, a
//! run recorded (the outcome, the checksum, each interface's switches, the bodies' telemetry)
//! and compared with the host core's f32 stack of the same parameters, run here through the core's
//! scene interface (bit-identical
//! outcome, steps, checksum and switches expected).

use std::time::{Duration, Instant};

use anyhow::bail;
use meterstick_core::Real;
use meterstick_core::multibody::scenes::StackParams;
use meterstick_core::planar::{ContactMode, Direction};
use meterstick_core::scene::{
    LcpLayout, Outcome, Precision, SceneParams, SceneView, StackSetup, ViewVisitor,
};
use meterstick_link::host::{Link, REPLY_TIMEOUT};
use meterstick_link::{Command, ErrorCode, Mode, OutcomeCode, ParamId, Report};
use serde::Serialize;

use super::Observer;
use crate::bodies::BodiesRow;

/// The rig's stack parameters, read back with `GetParam` (every [`ParamId`] the stack has).
///
/// # Errors
/// A missing or unexpected reply.
pub fn read_stack_params(link: &mut Link) -> anyhow::Result<StackParams<f32>> {
    let mut p = StackParams::<f32>::default();
    for id in ParamId::ALL.into_iter().filter(|id| StackParams::<f32>::NAMES.contains(&id.name())) {
        match link.request(&Command::GetParam { id }, REPLY_TIMEOUT)? {
            Report::Param { value, .. } if p.set(id.name(), value) => {}
            other => bail!("GetParam {}: unexpected reply {other:?}", id.name()),
        }
    }
    Ok(p)
}

/// An interface switch: step, time (s), interface, mode.
pub type InterfaceSwitch = (u32, f32, u8, Mode);

/// Every body's telemetry of one step, as the rig sent it (`Report::Body`, one per body).
#[derive(Debug, Clone, PartialEq)]
pub struct BodiesFrame {
    /// The step (0: the start).
    pub step: u32,
    /// Simulated time (s).
    pub time: f32,
    /// Each body's `[x, y, theta, vx, vy, omega]`, from the bottom up (`NaN` for a body whose
    /// frame did not arrive).
    pub states: Vec<[f32; 6]>,
}

impl BodiesFrame {
    /// The frame as a row of `host-sim run`'s scenes of several bodies (`crate::bodies`), for its
    /// CSV (no interface forces: the link does not carry them).
    #[must_use]
    pub fn row(&self) -> BodiesRow {
        let f = |s: &[f32; 6], i: usize| [f64::from(s[i]), f64::from(s[i + 1]), f64::from(s[i + 2])];
        BodiesRow {
            t: f64::from(self.time),
            q: self.states.iter().map(|s| f(s, 0)).collect(),
            v: self.states.iter().map(|s| f(s, 3)).collect(),
            interface_forces: Vec::new(),
            corner_loads: Vec::new(),
            spatial: Vec::new(),
            contacts: Vec::new(),
        }
    }
}

/// A stack run as the rig reported it.
#[derive(Debug, Clone)]
pub struct StackRecording {
    /// The parameters the rig ran (read back before the start).
    pub params: StackParams<f32>,
    /// The rig's outcome code, end time (s), steps and checksum.
    pub outcome: OutcomeCode,
    /// Simulated time at the end (s).
    pub end_time: f32,
    /// Steps.
    pub steps: u32,
    /// The rig's checksum of the run.
    pub checksum: u32,
    /// Each interface's switches.
    pub switches: Vec<InterfaceSwitch>,
    /// `Report::Body` frames received.
    pub body_frames: u64,
    /// The bodies' telemetry, a frame per telemetry step (`Report::Body` gathered by step).
    pub frames: Vec<BodiesFrame>,
    /// Reports the rig said it dropped.
    pub dropped: u32,
    /// Wall time from start to outcome (s).
    pub wall_s: f64,
}

/// Records a stack run until its outcome: with `start`, sends `Start` first; otherwise waits for
/// a run to begin.
///
/// # Errors
/// The start refused, no outcome within `timeout`, or the link failed.
pub fn record_stack_run(
    link: &mut Link,
    params: StackParams<f32>,
    start: bool,
    timeout: Duration,
    observer: &mut dyn Observer,
) -> anyhow::Result<StackRecording> {
    let began = Instant::now();
    if start {
        match link.request(&Command::Start, REPLY_TIMEOUT)? {
            Report::Ack { .. } => {}
            other => bail!("the rig refused to start: {other:?}"),
        }
    }
    let deadline = began + timeout;
    let (mut switches, mut body_frames, mut dropped) = (Vec::new(), 0u64, 0u32);
    let mut frames: Vec<BodiesFrame> = Vec::new();
    loop {
        let left = deadline.saturating_duration_since(Instant::now());
        let Some(report) = link.next(left.min(Duration::from_secs(1)))? else {
            if Instant::now() >= deadline {
                bail!("no outcome within {:.0} s", timeout.as_secs_f64());
            }
            continue;
        };
        observer.report(&report);
        match report {
            Report::Body { step, time, body, state, .. } => {
                body_frames += 1;
                if frames.last().is_none_or(|f| f.step != step) {
                    frames.push(BodiesFrame { step, time, states: Vec::new() });
                }
                if let Some(f) = frames.last_mut() {
                    let b = usize::from(body);
                    if f.states.len() <= b {
                        f.states.resize(b + 1, [f32::NAN; 6]);
                    }
                    f.states[b] = state;
                }
            }
            Report::InterfaceSwitch { step, time, interface, mode } => {
                switches.push((step, time, interface, mode));
            }
            Report::Error(ErrorCode::TxDropped { count }) => dropped = dropped.saturating_add(count),
            Report::Outcome { outcome, time, steps, checksum } => {
                return Ok(StackRecording {
                    params,
                    outcome,
                    end_time: time,
                    steps,
                    checksum,
                    switches,
                    body_frames,
                    frames,
                    dropped,
                    wall_s: began.elapsed().as_secs_f64(),
                });
            }
            _ => {}
        }
    }
}

/// An interface's mode from its four candidates, by the rule the link documents ([`Mode`]):
/// sliding when one slides; else by the touching (sticking) candidates: none separated, one
/// tipping, more sticking.
#[must_use]
pub fn interface_mode(candidates: [ContactMode; 4]) -> Mode {
    if let Some(ContactMode::Sliding(d)) = candidates.iter().find(|m| m.is_sliding()) {
        return if *d == Direction::Plus { Mode::SlidingPositive } else { Mode::SlidingNegative };
    }
    match candidates.iter().filter(|m| **m == ContactMode::Sticking).count() {
        0 => Mode::Separated,
        1 => Mode::Tipping,
        _ => Mode::Sticking,
    }
}

/// A stack run recorded from the rig against the host core's.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
#[allow(clippy::struct_excessive_bools)] // one verdict per figure compared
pub struct StackComparison {
    /// Same outcome.
    pub same_outcome: bool,
    /// Same number of steps.
    pub same_steps: bool,
    /// Same checksum (every block's state after every step, bit-identical).
    pub same_checksum: bool,
    /// Same interface switches (step, time, interface, mode).
    pub same_switches: bool,
    /// The rig's checksum.
    pub rig_checksum: String,
    /// The host's.
    pub host_checksum: String,
}

impl StackComparison {
    /// Everything the same.
    #[must_use]
    pub const fn identical(&self) -> bool {
        self.same_outcome && self.same_steps && self.same_checksum && self.same_switches
    }
}

/// Runs the host core's f32 stack of the rig's parameters (`SceneParams::Stack`, through the
/// core's scene interface: the same scene the rig's `Stack3` is) and compares it with `rec`.
///
/// # Errors
/// Parameters the host core refuses.
pub fn compare_stack(rec: &StackRecording) -> anyhow::Result<StackComparison> {
    // The rig runs three blocks (`Stack3`).
    let spec = SceneParams::Stack(StackSetup { blocks: 3.0, params: rec.params.cast::<f64>() });
    let host = spec
        .build_view::<0, _>(Precision::F32, LcpLayout::Full, HostRun)
        .map_err(|e| anyhow::anyhow!("the rig's parameters: {e}"))?;
    let (outcome, steps, checksum, switches) = (host.outcome, host.steps, host.checksum, host.switches);
    Ok(StackComparison {
        same_outcome: super::outcome_of(rec.outcome).class == outcome.kind(),
        same_steps: steps == rec.steps,
        same_checksum: checksum == rec.checksum,
        same_switches: switches.len() == rec.switches.len()
            && switches
                .iter()
                .zip(&rec.switches)
                .all(|(h, r)| h.0 == r.0 && h.1.to_bits() == r.1.to_bits() && h.2 == r.2 && h.3 == r.3),
        rig_checksum: format!("{:08x}", rec.checksum),
        host_checksum: format!("{checksum:08x}"),
    })
}

/// The host's run of the stack: its outcome, steps, checksum and interface switches `(step, time,
/// interface, mode)`.
struct HostStack {
    outcome: Outcome,
    steps: u32,
    checksum: u32,
    switches: Vec<(u32, f32, u8, Mode)>,
}

/// Steps a scene of several bodies to its outcome through its view, reading each interface's mode
/// from its four candidate contacts (the view lists them pair by pair).
struct HostRun;

impl ViewVisitor for HostRun {
    type Output = HostStack;

    fn visit<T: Real>(self, view: &mut dyn SceneView<T>) -> HostStack {
        let interfaces = |view: &dyn SceneView<T>| -> Vec<Mode> {
            (0..view.contact_count() / 4)
                .map(|p| {
                    interface_mode(core::array::from_fn(|c| {
                        view.contact(4 * p + c).map_or(ContactMode::Separated, |x| x.mode)
                    }))
                })
                .collect()
        };
        let mut last = interfaces(view);
        let (mut steps, mut switches) = (0u32, Vec::new());
        while view.step() {
            steps += 1;
            let now = interfaces(view);
            for (i, (a, b)) in last.iter().zip(&now).enumerate() {
                if a != b {
                    let time = view.time().as_f64() as f32;
                    switches.push((steps, time, u8::try_from(i).unwrap_or(u8::MAX), *b));
                }
            }
            last = now;
        }
        HostStack {
            outcome: view.outcome().unwrap_or(Outcome::Unfinished),
            steps,
            checksum: view.checksum(),
            switches,
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::panic, clippy::float_cmp)]
mod tests {
    use meterstick_core::multibody::scenes::{MultibodyScene as _, Stack3};
    use meterstick_core::planar::Checksum;

    use super::*;

    /// The rig's side of a run, as the rig steps it: its concrete `Stack3`, the checksum of every
    /// block after every step, each interface's switches.
    fn rig_run(params: StackParams<f32>) -> StackRecording {
        let mut scene = Stack3::<f32>::new(params).unwrap();
        let mut checksum = Checksum::new();
        let mut last = scene.modes().map(interface_mode);
        let (mut steps, mut switches) = (0u32, Vec::new());
        let outcome = scene.run(|r| {
            steps += 1;
            r.states.iter().for_each(|b| checksum.add(b));
            let now = r.modes.map(interface_mode);
            for (i, (a, b)) in last.iter().zip(&now).enumerate() {
                if a != b {
                    switches.push((steps, r.time, u8::try_from(i).unwrap(), *b));
                }
            }
            last = now;
        });
        let code = match outcome {
            Outcome::Held => OutcomeCode::Held,
            Outcome::Fell => OutcomeCode::Fell,
            other => panic!("the stack ended {other:?}"),
        };
        StackRecording {
            params,
            outcome: code,
            end_time: scene.time(),
            steps,
            checksum: checksum.value(),
            switches,
            body_frames: 0,
            frames: Vec::new(),
            dropped: 0,
            wall_s: 0.0,
        }
    }

    /// The host's run through the scene interface is the rig's concrete run, bit for bit (the
    /// stack held at overhang 0.98 and fallen at 1.02), and a run that differs in its checksum, its
    /// steps or a switch's time is told apart.
    #[test]
    fn the_host_run_through_the_view_is_the_rigs() {
        for overhang in [0.98, 1.02] {
            let params = StackParams { overhang, max_time: 2.0, ..StackParams::default() };
            let rec = rig_run(params);
            assert!(!rec.switches.is_empty() || overhang < 1.0, "the falling stack switched");
            let cmp = compare_stack(&rec).unwrap();
            assert!(cmp.identical(), "overhang {overhang}: {cmp:?}");
            let mut other = rec.clone();
            other.checksum ^= 1;
            assert!(!compare_stack(&other).unwrap().same_checksum);
            let mut other = rec.clone();
            other.steps += 1;
            assert!(!compare_stack(&other).unwrap().same_steps);
            if let Some(first) = other.switches.first_mut() {
                first.1 = f32::from_bits(first.1.to_bits() + 1);
                assert!(!compare_stack(&other).unwrap().same_switches);
            }
        }
    }

    /// A frame's row: each body's pose and velocity, exactly (f32 widened), time in `t`, and no
    /// interface forces (the link does not carry them).
    #[test]
    fn a_frame_is_a_row_of_the_scenes_of_several_bodies() {
        let frame = BodiesFrame {
            step: 10,
            time: 0.01,
            states: vec![[1.0, 2.0, 0.1, 3.0, 4.0, 0.5], [0.1, 0.3, -0.2, 1e-7, -2.0, 6.0]],
        };
        let row = frame.row();
        assert_eq!(row.t, f64::from(0.01f32));
        assert_eq!(
            row.q,
            vec![[1.0, 2.0, f64::from(0.1f32)], [f64::from(0.1f32), f64::from(0.3f32), f64::from(-0.2f32)]]
        );
        assert_eq!(row.v, vec![[3.0, 4.0, 0.5], [f64::from(1e-7f32), -2.0, 6.0]]);
        assert!(row.interface_forces.is_empty() && row.corner_loads.is_empty());
        let dir = std::env::temp_dir().join(format!("meterstick-bodies-frame-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("rig.csv");
        crate::bodies::write_trajectory(&[row], &path).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        let mut lines = text.lines();
        assert_eq!(lines.next(), Some("t,x0,y0,theta0,vx0,vy0,omega0,x1,y1,theta1,vx1,vy1,omega1"), "{text}");
        let values: Vec<f64> = lines.next().unwrap().split(',').map(|v| v.parse().unwrap()).collect();
        assert_eq!(values.len(), 13);
        assert_eq!(values[7], f64::from(0.1f32));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
