//! The wire types: what the host sends ([`Command`]), what the rig sends ([`Report`]), and the
//! small enums and structs they carry.
//!
//! Every type here is plain data, independent of `meterstick-core` (whose types are free to
//! change): the firmware maps between the two. Enums are encoded by postcard as a varint of the
//! variant's index in declaration order, so **the order of variants is part of the protocol**:
//! new variants go at the end, and any change bumps [`PROTOCOL_VERSION`](crate::PROTOCOL_VERSION).
//! A tag the receiver does not know fails decoding and is counted in
//! [`LinkStats::decode_errors`].

use serde::{Deserialize, Serialize};

use crate::LinkStats;

/// A parameter of the rig's scene the teacher can set with [`Command::SetParam`]: the meter
/// stick's, and (since protocol version 7) the stack's; a name both scenes have (`MuStatic`,
/// `Step`, `MaxTime`, ...) is each scene's parameter of that name. Values are `f32` in SI units;
/// the rig's core validates them and answers [`Report::Rejected`] naming the parameter when it
/// refuses one ([`RejectReason::Other`] for a parameter its scene does not have).
///
/// Coordinates as in the core: `x` to the right along the rod at rest, `y` up, origin at the
/// rod's centre of mass at the start.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ParamId {
    /// Start `x` of finger 1 (left), relative to the rod's centre of mass (m).
    Finger1X,
    /// Start `x` of finger 2 (right) (m).
    Finger2X,
    /// Height `y` of finger 1's tip (m).
    Finger1Y,
    /// Height `y` of finger 2's tip (m).
    Finger2Y,
    /// Velocity of finger 1 along `x` (m/s; positive to the right).
    Finger1Velocity,
    /// Velocity of finger 2 along `x` (m/s; positive to the right).
    Finger2Velocity,
    /// Finger width (m): the fingers stop when their tips are this far apart.
    FingerWidth,
    /// Static friction coefficient (dimensionless).
    MuStatic,
    /// Kinetic friction coefficient (dimensionless, at most `MuStatic`).
    MuKinetic,
    /// Rod length (m).
    RodLength,
    /// Rod thickness (m).
    RodThickness,
    /// Rod mass (kg).
    RodMass,
    /// Gravitational acceleration (m/s^2, acting in `-y`).
    Gravity,
    /// Time step `h` (s).
    Step,
    /// A contact whose slip speed is at most this sticks (m/s).
    StickSpeed,
    /// The rod has fallen when it tilted more than this from its start angle (rad). Since
    /// protocol version 2.
    TiltLimit,
    /// The rod has fallen when its centre of mass dropped this far (m). Since version 2.
    DropLimit,
    /// After the fingers meet, the rod must stay on them this long to balance (s). Since
    /// version 2.
    HoldTime,
    /// A run ends unfinished at this simulated time (s). Since version 2.
    MaxTime,
    /// The stack's block length `L` (m). Since version 7.
    Length,
    /// The stack's block height (m). Since version 7.
    Height,
    /// The stack's block mass (kg, each). Since version 7.
    Mass,
    /// The stack's overhang scale `s`: the `k`-th block from the top reaches `s L / (2k)` beyond
    /// the one under it (1 the critical stack; dimensionless). Since version 7.
    Overhang,
    /// The stack's contact margin: a corner within it of a face is a candidate contact (m).
    /// Since version 7.
    ContactMargin,
}

impl ParamId {
    /// Every parameter, in tag order.
    pub const ALL: [Self; 24] = [
        Self::Finger1X,
        Self::Finger2X,
        Self::Finger1Y,
        Self::Finger2Y,
        Self::Finger1Velocity,
        Self::Finger2Velocity,
        Self::FingerWidth,
        Self::MuStatic,
        Self::MuKinetic,
        Self::RodLength,
        Self::RodThickness,
        Self::RodMass,
        Self::Gravity,
        Self::Step,
        Self::StickSpeed,
        Self::TiltLimit,
        Self::DropLimit,
        Self::HoldTime,
        Self::MaxTime,
        Self::Length,
        Self::Height,
        Self::Mass,
        Self::Overhang,
        Self::ContactMargin,
    ];

    /// The parameter's name in snake case, as the core's and `host-sim`'s parameters are
    /// spelled (`"finger1_x"`, `"mu_static"`, ...): for messages such as "rejected: mu_kinetic
    /// above mu_static".
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Finger1X => "finger1_x",
            Self::Finger2X => "finger2_x",
            Self::Finger1Y => "finger1_y",
            Self::Finger2Y => "finger2_y",
            Self::Finger1Velocity => "finger1_velocity",
            Self::Finger2Velocity => "finger2_velocity",
            Self::FingerWidth => "finger_width",
            Self::MuStatic => "mu_static",
            Self::MuKinetic => "mu_kinetic",
            Self::RodLength => "rod_length",
            Self::RodThickness => "rod_thickness",
            Self::RodMass => "rod_mass",
            Self::Gravity => "gravity",
            Self::Step => "step",
            Self::StickSpeed => "stick_speed",
            Self::TiltLimit => "tilt_limit",
            Self::DropLimit => "drop_limit",
            Self::HoldTime => "hold_time",
            Self::MaxTime => "max_time",
            Self::Length => "length",
            Self::Height => "height",
            Self::Mass => "mass",
            Self::Overhang => "overhang",
            Self::ContactMargin => "contact_margin",
        }
    }

    /// The SI unit of the parameter's value (`""` for the friction coefficients).
    #[must_use]
    pub const fn unit(self) -> &'static str {
        match self {
            Self::Finger1X
            | Self::Finger2X
            | Self::Finger1Y
            | Self::Finger2Y
            | Self::FingerWidth
            | Self::RodLength
            | Self::RodThickness
            | Self::DropLimit
            | Self::Length
            | Self::Height
            | Self::ContactMargin => "m",
            Self::Finger1Velocity | Self::Finger2Velocity | Self::StickSpeed => "m/s",
            Self::MuStatic | Self::MuKinetic | Self::Overhang => "",
            Self::RodMass | Self::Mass => "kg",
            Self::Gravity => "m/s^2",
            Self::Step | Self::HoldTime | Self::MaxTime => "s",
            Self::TiltLimit => "rad",
        }
    }
}

/// A preset scene the firmware knows ([`Command::Preset`]): only an id; the firmware maps it
/// to a full parameter set.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Preset {
    /// The paper's slow finger: 0.1 m/s (the rod balances).
    Slow,
    /// A fast finger: 5 m/s (the rod falls).
    Fast,
    /// Near the fall threshold, e.g. 0.3 m/s: the outcome is sensitive to the parameters.
    NearThreshold,
}

impl Preset {
    /// Every preset, in tag order.
    pub const ALL: [Self; 3] = [Self::Slow, Self::Fast, Self::NearThreshold];
}

/// The scene the rig runs, announced in [`Report::Hello`] and chosen with
/// [`Command::SelectScene`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum SceneId {
    /// A rod on two fingers, one moving toward the other (Leong & Lv).
    MeterStick,
    /// A block on an incline.
    Incline,
    /// A ladder against a wall.
    Ladder,
    /// Three blocks stacked over a table's edge at harmonic overhangs: the rig's lights show each
    /// interface's mode (table-block 1, block 1-block 2, block 2-block 3). Since version 7.
    Stack,
}

/// The mode of one contact, or (since protocol version 7) of an interface between two bodies,
/// from its candidate contacts: [`Self::Sticking`] when at least two touch and none slides,
/// sliding when one slides, [`Self::Tipping`] when exactly one touches (and sticks),
/// [`Self::Separated`] when none touches.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Mode {
    /// No contact force (the rod left the finger).
    Separated,
    /// Normal force, no slip.
    Sticking,
    /// Sliding, the rod moving in `+x` relative to the finger.
    SlidingPositive,
    /// Sliding, the rod moving in `-x` relative to the finger.
    SlidingNegative,
    /// An interface whose whole load is on one corner, which sticks: the upper body pivots
    /// about it (a stack falling over the table's edge). Since version 7.
    Tipping,
}

/// How a run ended ([`Report::Outcome`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum OutcomeCode {
    /// The fingers met under the rod and it stayed on them (the trick worked).
    Balanced,
    /// The rod fell off the fingers.
    Fell,
    /// The rod is held (a static scene at rest).
    Held,
    /// The body slid (incline, ladder).
    Slid,
    /// The body tipped over.
    Tipped,
    /// The run reached its time limit, or was stopped, without an outcome.
    Unfinished,
    /// The LCP solver failed on a step.
    SolverFailed,
    /// The state became NaN or infinite.
    NonFinite,
    /// The reduced (6x6) model left its range of validity and no fallback was linked.
    ReducedModelLeftRange,
    /// The rig's actuator could not follow the scene (more stepper pulses due in one tick than
    /// it can emit); the rig stopped in [`RigState::Fault`].
    ActuatorOverrun,
    /// The body rolled without slipping (a cylinder on an incline). Since version 5.
    Rolled,
    /// A sliding end stopped within one step under an impulsive friction (Painlevé's rod).
    /// Since version 5.
    Jammed,
    /// The lower body slid on the floor with the upper one riding on it, never sliding
    /// (block-on-block, the tablecloth). Since version 5.
    Rode,
    /// The board came out from under the block, which came to rest behind it (the tablecloth).
    /// Since version 5.
    Stayed,
    /// A sliding body came to rest (the puck). Since version 6.
    Stopped,
}

/// The rig's run state ([`Report::State`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum RigState {
    /// Parameters may be set; waiting for [`Command::Start`].
    Waiting,
    /// A run is in progress.
    Running,
    /// The run ended ([`Report::Outcome`] was sent); [`Command::Reset`] returns to `Waiting`.
    Finished,
    /// The rig hit a fault (see the preceding [`Report::Error`]); [`Command::Reset`] clears it.
    Fault,
}

/// Why the core refused a parameter ([`Report::Rejected`]); mirrors the core's validation
/// errors.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum RejectReason {
    /// The value is NaN or infinite.
    NotFinite,
    /// The value must be positive.
    NotPositive,
    /// The value must not be negative.
    Negative,
    /// `mu_kinetic` would exceed `mu_static`.
    KineticAboveStatic,
    /// A finger would start beyond an end of the rod.
    FingerOutsideRod,
    /// Finger 1 would not start left of finger 2 by more than the finger width.
    FingersCrossed,
    /// Parameters cannot change while a run is in progress.
    Busy,
    /// Any other reason.
    Other,
    /// Valid for the model, but beyond what the rig can perform: a finger speed its carriage
    /// cannot follow, a finger motion its hardware lacks (finger 2 is fixed, finger 1 only
    /// approaches it), or a step its timer cannot tick in real time.
    BeyondRig,
    /// The value is outside its range: a step longer than the run, a rod at least as thick as
    /// it is long, a limit beyond the model's.
    OutOfRange,
    /// The rod's mass and size give a moment of inertia the rig's `f32` cannot hold (their
    /// product underflows to 0 or overflows).
    InertiaOutOfRange,
}

impl RejectReason {
    /// What the reason says, in words, for a message about the parameter refused ("the rig
    /// refused --set step=100: it is outside its range").
    #[must_use]
    pub const fn words(self) -> &'static str {
        match self {
            Self::NotFinite => "it is not a finite number",
            Self::NotPositive => "it must be positive",
            Self::Negative => "it must not be negative",
            Self::KineticAboveStatic => "the kinetic friction coefficient would exceed the static one",
            Self::FingerOutsideRod => "a finger would start beyond an end of the rod",
            Self::FingersCrossed => "finger 1 would not start left of finger 2 by more than the finger width",
            Self::Busy => "a run is in progress",
            Self::Other => "the rig gave no reason",
            Self::BeyondRig => "the model accepts it, but the rig cannot perform it",
            Self::OutOfRange => {
                "it is outside its range (a step longer than the run, a rod as thick as long)"
            }
            Self::InertiaOutOfRange => {
                "with the rod's mass and length it gives a moment of inertia f32 cannot hold"
            }
        }
    }
}

/// The data-free tag of a [`Command`], acknowledged by [`Report::Ack`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum CommandTag {
    /// [`Command::Hello`].
    Hello,
    /// [`Command::SetParam`].
    SetParam,
    /// [`Command::Preset`].
    Preset,
    /// [`Command::Start`].
    Start,
    /// [`Command::Stop`].
    Stop,
    /// [`Command::Reset`].
    Reset,
    /// [`Command::SetTelemetry`].
    SetTelemetry,
    /// [`Command::GetStats`].
    GetStats,
    /// [`Command::Ping`].
    Ping,
    /// [`Command::GetParam`] (since protocol version 2).
    GetParam,
    /// [`Command::SelectScene`] (since protocol version 7).
    SelectScene,
}

/// A rig-side error ([`Report::Error`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ErrorCode {
    /// The command is not allowed in the rig's current state (e.g. `Start` while running).
    NotAllowed {
        /// The refused command.
        command: CommandTag,
        /// The rig's state when it was refused.
        state: RigState,
    },
    /// Reports were dropped because the transmit path was full (the telemetry rate is too
    /// high for the link); `count` reports since the last such error.
    TxDropped {
        /// Reports dropped.
        count: u32,
    },
    /// The receive hardware lost bytes (e.g. a UART overrun).
    RxOverrun,
    /// The core faulted; the rig is now in [`RigState::Fault`].
    CoreFault,
    /// A firmware-specific error number.
    Other(u16),
    /// The rig's actuator could not follow the scene (see [`OutcomeCode::ActuatorOverrun`]); the
    /// rig is now in [`RigState::Fault`].
    ActuatorOverrun,
    /// The rig does not run this scene ([`Command::SelectScene`]). Since protocol version 7.
    NoSuchScene(SceneId),
}

/// One contact's part of a [`Report::Telemetry`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ContactTelemetry {
    /// The contact's mode at the end of the step.
    pub mode: Mode,
    /// Normal impulse over the step (N s).
    pub normal_impulse: f32,
    /// Friction (tangential) impulse over the step (N s, along `+x` of the rod).
    pub friction_impulse: f32,
}

/// Host to rig. The rig answers every command it decodes with exactly one report:
///
/// | command | reply |
/// |---|---|
/// | `Hello` | [`Report::Hello`] |
/// | `SetParam` | [`Report::Ack`], or [`Report::Rejected`] naming the parameter |
/// | `Preset` | [`Report::Ack`], [`Report::Error`] with [`ErrorCode::NotAllowed`], or [`Report::Rejected`] naming a parameter of the preset the rig cannot perform |
/// | `Start`, `Stop`, `Reset`, `SetTelemetry` | [`Report::Ack`], or [`Report::Error`] with [`ErrorCode::NotAllowed`] |
/// | `GetStats` | [`Report::Stats`] (the rig's receive counters) |
/// | `Ping` | [`Report::Pong`] with the same nonce |
/// | `GetParam` | [`Report::Param`] with the value the next (or current) run uses |
/// | `SelectScene` | [`Report::Ack`] then the new scene's [`Report::Hello`] and [`Report::State`]; [`Report::Error`] with [`ErrorCode::NotAllowed`] while running, or [`ErrorCode::NoSuchScene`] |
///
/// A frame that fails to decode gets no reply (it is counted): the host times out and may
/// retry, or ask [`Command::GetStats`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Command {
    /// Ask for [`Report::Hello`]. Tag 0 in every protocol version.
    Hello,
    /// Set one parameter (validated by the core; applies to the next run).
    SetParam {
        /// Which parameter.
        id: ParamId,
        /// Its value, SI units (see [`ParamId`]).
        value: f32,
    },
    /// Load a preset parameter set.
    Preset(Preset),
    /// Start a run with the current parameters.
    Start,
    /// Stop the run (the outcome is [`OutcomeCode::Unfinished`]).
    Stop,
    /// Back to [`RigState::Waiting`] with the current parameters (clears a fault).
    Reset,
    /// Send [`Report::Telemetry`] every `every_n_steps` steps; 0 turns telemetry off.
    /// Default [`DEFAULT_TELEMETRY_EVERY`](crate::DEFAULT_TELEMETRY_EVERY).
    SetTelemetry {
        /// Decimation: one telemetry report every this many steps (0 = off).
        every_n_steps: u16,
    },
    /// Ask for [`Report::Stats`].
    GetStats,
    /// Ask for [`Report::Pong`] echoing `nonce` (liveness, round-trip time).
    Ping {
        /// Echoed back.
        nonce: u32,
    },
    /// Ask for [`Report::Param`]: the value of one parameter as the rig holds it (what the
    /// next run uses, or the current run while one is in progress). With all of
    /// [`ParamId::ALL`] the host knows the rig's whole parameter set, e.g. to run the same
    /// scene itself (since protocol version 2).
    GetParam {
        /// Which parameter.
        id: ParamId,
    },
    /// Run another scene the rig has (its default parameters; not while a run is in progress).
    /// Since protocol version 7.
    SelectScene(SceneId),
}

impl Command {
    /// The command's data-free tag.
    #[must_use]
    pub const fn tag(&self) -> CommandTag {
        match self {
            Self::Hello => CommandTag::Hello,
            Self::SetParam { .. } => CommandTag::SetParam,
            Self::Preset(_) => CommandTag::Preset,
            Self::Start => CommandTag::Start,
            Self::Stop => CommandTag::Stop,
            Self::Reset => CommandTag::Reset,
            Self::SetTelemetry { .. } => CommandTag::SetTelemetry,
            Self::GetStats => CommandTag::GetStats,
            Self::Ping { .. } => CommandTag::Ping,
            Self::GetParam { .. } => CommandTag::GetParam,
            Self::SelectScene(_) => CommandTag::SelectScene,
        }
    }
}

/// Rig to host. The rig sends [`Report::Hello`] then [`Report::State`] at boot, unasked;
/// after that, one reply per command (see [`Command`]) and, while running, telemetry,
/// switch events, the outcome and real-time margins.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Report {
    /// Who the rig is. Tag 0 with `protocol` first in every protocol version, so a host can
    /// always read the rig's protocol version (fields are only ever appended to it).
    Hello {
        /// The rig's [`PROTOCOL_VERSION`](crate::PROTOCOL_VERSION).
        protocol: u16,
        /// Firmware version (major, minor, patch).
        firmware: (u8, u8, u8),
        /// Core version (major, minor, patch).
        core: (u8, u8, u8),
        /// Build id, e.g. the first 8 characters of the git hash in ASCII.
        build: [u8; 8],
        /// The scene the firmware runs.
        scene: SceneId,
        /// The LCP size of the scene (the meter stick's 6 or 8; the stack's rows, 32 for three
        /// blocks).
        lcp_size: u8,
        /// The time step (us).
        step_us: u32,
    },
    /// The state after a step, every `every_n_steps` steps.
    Telemetry {
        /// Step number (0 = the initial state).
        step: u32,
        /// Simulated time (s).
        time: f32,
        /// The rod's state: `x`, `y` (m), `theta` (rad), `vx`, `vy` (m/s), `omega` (rad/s).
        state: [f32; 6],
        /// Finger tip `x` positions (m).
        fingers: [f32; 2],
        /// The two contacts (finger 1, finger 2).
        contacts: [ContactTelemetry; 2],
    },
    /// A contact changed mode on this step (sent whatever the telemetry rate).
    Switch {
        /// Step number.
        step: u32,
        /// Simulated time (s).
        time: f32,
        /// The contact (0 = finger 1, 1 = finger 2).
        contact: u8,
        /// Its new mode.
        mode: Mode,
        /// Each finger's position along the rod, relative to the centre of mass (m).
        along: [f32; 2],
    },
    /// The run ended.
    Outcome {
        /// How.
        outcome: OutcomeCode,
        /// Simulated time at the end (s).
        time: f32,
        /// Steps taken.
        steps: u32,
        /// A checksum of the trajectory (firmware-defined), to compare runs across builds.
        checksum: u32,
    },
    /// Real-time margin of the step loop since the run started (or the last `Margin`).
    Margin {
        /// The longest step (CPU cycles; under QEMU, SysTick ticks).
        worst_cycles: u32,
        /// The step period (CPU cycles; 0 when the rig does not run in real time).
        period_cycles: u32,
        /// Steps that missed their deadline.
        overruns: u32,
        /// The step number of the longest step (since protocol version 2).
        worst_step: u32,
    },
    /// The command was carried out.
    Ack {
        /// Which command.
        command: CommandTag,
    },
    /// A [`Command::SetParam`] was refused.
    Rejected {
        /// The parameter.
        id: ParamId,
        /// Why.
        reason: RejectReason,
    },
    /// A rig-side error.
    Error(ErrorCode),
    /// The rig's receive counters ([`FrameDecoder::stats`](crate::FrameDecoder::stats)).
    Stats(LinkStats),
    /// Reply to [`Command::Ping`].
    Pong {
        /// The ping's nonce.
        nonce: u32,
    },
    /// The rig's run state (on change, and after [`Report::Hello`]).
    State(RigState),
    /// Reply to [`Command::GetParam`] (since protocol version 2).
    Param {
        /// The parameter.
        id: ParamId,
        /// Its value (SI units, see [`ParamId`]).
        value: f32,
    },
    /// One body's state after a step of a scene of several bodies, every `every_n_steps` steps:
    /// one report per body, in the scene's body order (the stack: from the bottom block up), all
    /// with the same `step` (since protocol version 7).
    Body {
        /// Step number (0 = the initial state).
        step: u32,
        /// Simulated time (s).
        time: f32,
        /// The body (0 = the first).
        body: u8,
        /// Its state: `x`, `y` (m), `theta` (rad), `vx`, `vy` (m/s), `omega` (rad/s).
        state: [f32; 6],
        /// The mode of the interface the body rests on (the stack: body `i` on interface `i`,
        /// the bottom block on the table).
        mode: Mode,
    },
    /// An interface between two bodies changed mode on this step (sent whatever the telemetry
    /// rate; since protocol version 7).
    InterfaceSwitch {
        /// Step number.
        step: u32,
        /// Simulated time (s).
        time: f32,
        /// The interface (the stack: 0 = the table and the bottom block).
        interface: u8,
        /// Its new mode.
        mode: Mode,
    },
}
