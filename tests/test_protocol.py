"""Protocol segments: validation, and the velocity/duration/target each gives a plate."""

import math
from dataclasses import dataclass, field

import pytest

from gecko_agents import protocol as pr


@dataclass
class FakePlate:
    """Just what a segment may ask of the model (protocol.Plate)."""

    dt: float = 0.1
    time: float = 0.0
    plate_position: tuple = (0.0, 10.0)
    z_touch: float = 9.0
    plate_start: float = 10.0
    settle_time: float = 1.0
    pull_travel: float = 20.0
    n: int = 1
    deepest: float = -9.0
    force: float = 0.0
    attached: int = 0
    log: list = field(default_factory=list)

    def normal_force(self):
        return self.force

    def n_attached(self):
        return self.attached


def _drive(seg, plate, max_steps=100_000):
    """Integrate the plate position through a segment; returns the number of steps."""
    state = {"start": plate.plate_position, "t0": plate.time}
    for n in range(max_steps):
        v = seg.velocity(plate, state)
        if v is None:
            return n
        x, y = plate.plate_position
        plate.plate_position = (x + v[0] * plate.dt, y + v[1] * plate.dt)
        plate.time += plate.dt
    raise AssertionError("segment never ended")


def test_move_lands_exactly_on_its_target():
    plate = FakePlate()
    seg = pr.Move(dx=1.0, dy=-0.55, speed=0.5)
    n = _drive(seg, plate)
    assert plate.plate_position == pytest.approx((1.0, 10.0 - 0.55), abs=1e-12)
    assert n == math.ceil(math.hypot(1.0, 0.55) / (0.5 * 0.1))
    assert seg.estimated_duration(plate) == pytest.approx(math.hypot(1.0, 0.55) / 0.5)
    assert seg.skips_free_travel


def test_press_to_goes_to_depth_below_touch_down():
    plate = FakePlate()
    seg = pr.PressTo(0.3, speed=0.2)
    assert seg.target(plate, {"start": (0.0, 10.0)}) == (0.0, 9.0 - 0.3)
    _drive(seg, plate)
    assert plate.plate_position[1] == pytest.approx(8.7, abs=1e-12)
    assert seg.estimated_duration(plate) == pytest.approx((10.0 - 8.7) / 0.2)


def test_press_stops_once_the_averaged_force_reaches_the_preload():
    plate = FakePlate(settle_time=0.1)  # averaging window = one step: no lag
    seg = pr.Press(5.0, speed=1.0)
    state = {"start": plate.plate_position, "t0": 0.0}
    assert seg.velocity(plate, state) == (0.0, -1.0)  # far from the target: full speed
    plate.force = 4.5
    v = seg.velocity(plate, state)
    assert v == pytest.approx((0.0, -1.0 * 0.5 / (0.2 * 5.0)))  # within the band: slower
    plate.force = 5.0
    assert seg.velocity(plate, state) is None
    assert seg.target(plate, state) is None


def test_hold_lasts_its_duration():
    plate = FakePlate()
    n = _drive(pr.Hold(1.0), plate)
    assert n == 10 and plate.plate_position == (0.0, 10.0)
    assert pr.Hold(2.5).estimated_duration(plate) == 2.5


def test_pull_off_ends_a_clearance_after_the_last_tip_lets_go():
    plate = FakePlate(attached=3)
    seg = pr.PullOff(speed=1.0, angle_deg=90.0, clearance=0.45)
    state = {"start": plate.plate_position, "t0": 0.0}
    for _ in range(5):
        v = seg.velocity(plate, state)
        assert v == pytest.approx((0.0, 1.0))
        plate.plate_position = (0.0, plate.plate_position[1] + 0.1)
    plate.attached = 0
    n = _drive(seg, plate)
    assert n == 5  # 0.45 µm of clearance at 0.1 µm a step: 5 steps


def test_pull_off_gives_up_at_max_travel_and_says_so():
    plate = FakePlate(attached=2)
    with pytest.warns(UserWarning, match="2 setae still attached"):
        _drive(pr.PullOff(speed=1.0, max_travel=0.25), plate)
    assert plate.plate_position[1] == pytest.approx(10.3, abs=1e-9)


def test_pull_off_direction():
    v = pr.PullOff(speed=2.0, angle_deg=30.0).velocity(
        FakePlate(attached=1), {"start": (0.0, 10.0)}
    )
    assert v == pytest.approx((2.0 * math.cos(math.radians(30)), 2.0 * math.sin(math.radians(30))))


@pytest.mark.parametrize(
    "bad",
    [
        lambda: pr.Move(),
        lambda: pr.Move(dx=1, speed=0),
        lambda: pr.PressTo(float("nan")),
        lambda: pr.Press(-1.0),
        lambda: pr.Hold(0.0),
        lambda: pr.PullOff(angle_deg=200.0),
        lambda: pr.PullOff(max_travel=-1.0),
    ],
)
def test_bad_segments_are_refused(bad):
    with pytest.raises(ValueError):
        bad()


def test_presets():
    assert pr.press_pull(0.5, 0.01) == [pr.PressTo(0.5, 0.01), pr.PullOff(0.01)]
    assert pr.preload_pull(3.0) == [pr.Press(3.0), pr.PullOff()]
    assert pr.drag_pull(3.0, 2.0, 60.0) == [
        pr.Press(3.0),
        pr.Move(dx=2.0),
        pr.PullOff(angle_deg=60.0),
    ]
    assert pr.drag_pull(3.0, 0.0) == [pr.Press(3.0), pr.PullOff()]
