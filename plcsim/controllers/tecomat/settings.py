"""The Tecomat profile's settings: every value the manual leaves open, chosen here and named.

Each field says what the manual states, what it leaves open (the G-number of ``spec/tecomat.md``'s
gap list) and what we chose. A course that knows its controller better changes the setting, not code.
"""

from __future__ import annotations

from dataclasses import dataclass

from plcsim.core.errors import ConfigurationError, LiteralError
from plcsim.core.literals import to_ns

TIME_BASES_NS = (10_000_000, 100_000_000, 1_000_000_000, 10_000_000_000)
"""Timer codes 0..3: 10 ms, 100 ms, 1 s, 10 s (manual §7.5.3; no code means 0)."""


@dataclass
class TecomatConfig:
    """Sizes, timing and the choices the manual leaves open (see each field)."""

    cycle: str | int = "1ms"
    """Duration of one program cycle (the manual gives none; as the S7 model's default)."""
    x_size: int = 128
    y_size: int = 128
    s_size: int = 64
    r_size: int = 8192
    """The scratchpad of the CPM-1D module (manual §4.1.1): X0..X127, Y0..Y127, S0..S63, R0..R8191."""
    retentive_r: tuple[int, int] = (0, 0)
    """Bytes ``[start, end)`` of R a warm restart keeps (manual: "the retentive part", size not given);
    none by default. A cold restart clears all of R."""
    clear_all_stacks: bool = False
    """G30: the manual clears stack A at every turnaround and names no other. False: only A is cleared
    (B..H keep their levels); True: all eight. Either way stack A is active when a cycle starts."""
    pop_fill_keeps_a7: bool = False
    """G31: what enters A7 when the stack drops: 0 (False) or a copy of the old A7 (True)."""
    timer_ticks: str = "per_timer"
    """G40: ``"per_timer"`` counts each timer's units from its own start (the manual's words "every time
    unit from the rising edge"); ``"global"`` adds the units each time base ticked between turnarounds."""
    timer_max: int = 65_535
    """G38: the maximum range of a timer word (units); S0.4/S0.5 and RTO's YC signal reaching it."""
    ctd_set_value: int = 0xFFFF
    """G20: the value CTD's SET input loads (the manual says only "sets the counter")."""
    ltb_reduced_index: bool = True
    """G42: after LTB, A1 holds the index reduced modulo (limit + 1) (True) or the index as given."""
    ci_in_compare: bool = True
    """G8: EQ/LT/GT compare A0 with (operand + CI), CI = S0.3, as the manual's schema prints "+ CI"."""
    p1_p4_rotation: bool = True
    """P1..P4 "four-phase" (Fig. 5 only): one of them per cycle, P1 in the first."""
    p5_p9_periods: tuple[str, ...] = ("10ms", "50ms", "100ms", "500ms", "1s")
    """P5..P9 "time-interleaved" (Fig. 5 only, no periods given): each runs at the first turnaround
    at or after its due time; these periods are our choice."""
    process_mask_byte: int = 24
    """P10..P40 run while their mask bit is set (manual: "the process mask in S", no address): bit k of
    the bytes from S24 (S24.0 = P10 ... S27.6 = P40); our choice."""
    event_enable_byte: int = 29
    """P41..P48 run at the turnaround after their event source k was raised, if bit S29.(k-1) is set
    (Fig. 5 shows S29.0 beside source 1); a source with its bit cleared is ignored."""
    final_after_eoc: bool = True
    """Whether P64 (the final process) still runs when EOC ended the cycle early (not stated)."""
    watchdog_jumps: int = 1_000_000
    """Backward jumps one cycle may make before the cycle-time watchdog stops the CPU (a jump loop;
    code without backward jumps always ends, so only they are counted)."""
    long_low_word_in_a0: bool = True
    """G16: a long operand (``RL10``, extended set) on the 16-bit stack, which the manual does not describe:
    LD takes two levels, the low word (R10, R11) in A0 and the high word (R12, R13) in A1 (True; as
    ``LD RW12`` then ``LD RW10``), or the high word in A0 (False); WR/WRC/PUT write them back the same way."""
    fuse: bool = True
    """Run straight-line instruction runs as one generated function each (:mod:`plcsim.controllers.tecomat.fused`);
    False runs every instruction's closure (same results, slower)."""
    rtc_start: str = "2024-07-01-08:00:00"
    """The real-time clock at power-on (S5..S12), a Monday."""

    def __post_init__(self) -> None:
        if self.timer_ticks not in ("per_timer", "global"):
            raise ConfigurationError(f"timer_ticks {self.timer_ticks!r}: use 'per_timer' or 'global'")
        if self.cycle_ns <= 0:
            raise ConfigurationError(f"cycle {self.cycle!r} must be positive")
        lo, hi = self.retentive_r
        if not 0 <= lo <= hi <= self.r_size:
            raise ConfigurationError(
                f"retentive_r {self.retentive_r}: a range [start, end) inside R0..R{self.r_size - 1}"
            )
        try:
            self.p5_p9_ns  # noqa: B018 - the periods must be durations
        except LiteralError as exc:
            raise ConfigurationError(f"p5_p9_periods: {exc}") from None

    @property
    def timer_dialect(self) -> str:
        """The trace's note of how timers behave: advanced at the turnaround, only when they run."""
        return f"tecomat ({self.timer_ticks})"

    @property
    def cycle_ns(self) -> int:
        return to_ns(self.cycle, "cycle")

    @property
    def p5_p9_ns(self) -> tuple[int, ...]:
        return tuple(to_ns(p, "P5..P9 period") for p in self.p5_p9_periods)
