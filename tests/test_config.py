"""Run configurations: parsing, defaults, record paths, and one clear error per bad input."""

from __future__ import annotations

import copy
import math
import shutil
from pathlib import Path

import pytest

import rocking as rk
from rocking.excitation.record import GroundMotion
from rocking.io.config import Config, ConfigError, load_config
from rocking.io.records import bundled_records, read_record
from rocking.stack import Stack

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = sorted((ROOT / "examples").glob("*.toml"))
RINALDI = "Northridge1994_RinaldiReceivingSta_228"

BASE = {
    "statue": {"width": 0.3, "height": 1.2, "mass": 100.0},
    "motion": {"kind": "harmonic", "amplitude": 3.0, "frequency": 1.5, "cycles": 2},
}

# A TOML file with every table, for the file-based error cases below.
TOML = """\
[statue]
width = 0.3
height = 1.2
mass = 100.0
restitution = 0.8
friction = { static = 0.5, kinetic = 0.4 }

[pedestal]
mass = 50.0
friction = { static = 0.2, kinetic = 0.15 }

[motion]
kind = "harmonic"
amplitude = 3.0
frequency = 1.5
cycles = 2

[simulation]
duration = 1.5
"""

# (id, old text, new text, dotted field the message must name, words it must contain)
BAD_TOML = [
    ("negative-width", "width = 0.3", "width = -1", "statue.width", "must be > 0, got -1"),
    ("zero-height", "height = 1.2", "height = 0", "statue.height", "must be > 0"),
    ("zero-mass", "mass = 100.0", "mass = 0.0", "statue.mass", "must be > 0"),
    ("negative-pedestal-mass", "mass = 50.0", "mass = -5.0", "pedestal.mass", "must be > 0"),
    ("unknown-key", "height = 1.2", "height = 1.2\nheigth = 2.0", "statue.heigth", "unknown key"),
    ("unknown-table", "[simulation]", "[simulaton]", "simulaton", "unknown key"),
    ("unknown-motion-kind", 'kind = "harmonic"', 'kind = "earthquake"', "motion.kind", "unknown motion kind"),
    ("missing-motion-kind", 'kind = "harmonic"', "", "motion.kind", "missing"),
    ("unknown-pulse-shape", 'kind = "harmonic"\namplitude = 3.0\nfrequency = 1.5\ncycles = 2',
     'kind = "pulse"\nshape = "triangle"\namplitude = 3.0', "motion.shape", "unknown pulse shape"),
    ("kinetic-above-static", "{ static = 0.5, kinetic = 0.4 }", "{ static = 0.5, kinetic = 0.6 }",
     "statue.friction.kinetic", "must be <= static"),
    ("pedestal-kinetic-above-static", "{ static = 0.2, kinetic = 0.15 }", "{ static = 0.2, kinetic = 0.3 }",
     "pedestal.friction.kinetic", "must be <= static"),
    ("negative-friction", "{ static = 0.5, kinetic = 0.4 }", "{ static = -0.5 }",
     "statue.friction.static", "must be >= 0"),
    ("restitution-above-1", "restitution = 0.8", "restitution = 1.2", "statue.restitution", "must be <= 1"),
    ("restitution-below-0", "restitution = 0.8", "restitution = -0.1", "statue.restitution", "must be >= 0"),
    ("missing-width", "width = 0.3\n", "", "statue.width", "missing"),
    ("missing-pedestal-friction", "mass = 50.0\nfriction = { static = 0.2, kinetic = 0.15 }", "mass = 50.0",
     "pedestal.friction", "missing"),
    ("missing-frequency", "frequency = 1.5\n", "", "motion.frequency", "missing"),
    ("string-for-number", "amplitude = 3.0", 'amplitude = "3.0"', "motion.amplitude", "must be a number"),
    ("nan", "amplitude = 3.0", "amplitude = nan", "motion.amplitude", "finite"),
    ("bad-form", "cycles = 2", 'cycles = 2\nform = "tan"', "motion.form", "'cos'"),
    ("bad-normal-force", "duration = 1.5", 'duration = 1.5\nnormal_force = "half"', "simulation.normal_force", "'paper'"),
    ("bad-impact", "duration = 1.5", 'duration = 1.5\nimpact = "elastic"', "simulation.impact", "'coulomb'"),
    ("zero-duration", "duration = 1.5", "duration = 0", "simulation.duration", "must be > 0"),
    ("fractional-max-events", "duration = 1.5", "duration = 1.5\nmax_events = 2.5", "simulation.max_events",
     "integer"),
    ("negative-pedestal-width", "mass = 50.0", "mass = 50.0\nwidth = -0.5", "pedestal.width", "must be > 0"),
    ("record-not-found", 'kind = "harmonic"\namplitude = 3.0\nfrequency = 1.5\ncycles = 2',
     'kind = "record"\npath = "no_such_record.AT2"', "motion.path", "not found"),
    ("record-scale-and-pga", 'kind = "harmonic"\namplitude = 3.0\nfrequency = 1.5\ncycles = 2',
     f'kind = "record"\npath = "{RINALDI}"\nscale = 2.0\npga = 3.0', "motion", "not both"),
    ("record-bad-units", 'kind = "harmonic"\namplitude = 3.0\nfrequency = 1.5\ncycles = 2',
     f'kind = "record"\npath = "{RINALDI}"\nunits = "furlongs"', "motion.units", "unknown acceleration units"),
    ("record-bad-format", 'kind = "harmonic"\namplitude = 3.0\nfrequency = 1.5\ncycles = 2',
     f'kind = "record"\npath = "{RINALDI}"\nformat = "wav"', "motion.format", "unknown record format"),
    ("record-negative-scale", 'kind = "harmonic"\namplitude = 3.0\nfrequency = 1.5\ncycles = 2',
     f'kind = "record"\npath = "{RINALDI}"\nscale = -2.0', "motion.scale", "must be > 0"),
    ("rectangle-without-width", 'kind = "harmonic"\namplitude = 3.0\nfrequency = 1.5\ncycles = 2',
     'kind = "pulse"\nshape = "rectangle"\namplitude = 3.0', "motion.width", "missing"),
]


def _bad_toml_text(old: str, new: str) -> str:
    assert old in TOML, old
    return TOML.replace(old, new, 1)


def _mutated(path: tuple[str, ...], value, *, delete: bool = False) -> dict:
    d = copy.deepcopy(BASE)
    cur = d
    for key in path[:-1]:
        cur = cur.setdefault(key, {})
    if delete:
        del cur[path[-1]]
    else:
        cur[path[-1]] = value
    return d


# ------------------------------------------------------------------------ examples
def test_examples_exist():
    names = {p.name for p in EXAMPLES}
    assert {"statue_on_pedestal.toml", "statue_alone_record.toml", "paper_fig10a.toml"} <= names


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.name)
def test_every_example_parses_into_specs(path):
    cfg = load_config(path)
    system, motion, options, duration = cfg.to_specs()
    assert isinstance(system, (rk.System, Stack))  # a stack file ([[blocks]]) gives a rocking.stack.Stack
    assert isinstance(options, rk.Options)
    assert duration is None or (duration > 0 and math.isfinite(duration))
    assert motion.pga > 0
    assert cfg.source == str(path)


def test_paper_fig10a_is_the_papers_case():
    system, motion, options, duration = load_config(ROOT / "examples/paper_fig10a.toml").to_specs()
    st, ped = system.statue, system.pedestal
    assert (st.width, st.height, st.mass, st.restitution) == (1.0, 4.0, 1.0, 0.8)
    assert ped.mass == 1.0 and (ped.friction.static, ped.friction.kinetic) == (0.4, 0.3)
    assert isinstance(motion, rk.Harmonic)
    assert (motion.amplitude, motion.frequency, motion.cycles, motion.form) == (6.75, 1.2, 30, "cos")
    assert options.gravity == 9.81
    assert duration == pytest.approx(25.0)


def test_statue_alone_record_example_uses_the_bundled_record_scaled():
    system, motion, _, duration = load_config(ROOT / "examples/statue_alone_record.toml").to_specs()
    assert system.pedestal is None
    assert (system.statue.width, system.statue.height) == (0.3, 1.2)
    assert system.statue.friction is not None  # it can slide on the floor
    assert isinstance(motion, GroundMotion) and motion.name == RINALDI
    raw = read_record(RINALDI)
    assert motion.pga != pytest.approx(raw.pga)  # scaled
    assert duration is None  # default: the record, then free motion until at rest


def test_statue_on_pedestal_example_has_both_interfaces():
    system, *_ = load_config(ROOT / "examples/statue_on_pedestal.toml").to_specs()
    assert system.pedestal is not None
    assert system.top_friction is not None and system.floor_friction is system.pedestal.friction


# ------------------------------------------------------------------- values/defaults
def test_dict_and_toml_give_the_same_specs(tmp_path):
    f = tmp_path / "c.toml"
    f.write_text(TOML, encoding="utf-8")
    import tomllib

    a = load_config(f).to_specs()
    b = load_config(tomllib.loads(TOML)).to_specs()
    assert a == b


def test_defaults_follow_the_api():
    cfg = load_config(BASE)
    system, motion, options, duration = cfg.to_specs()
    assert options == rk.Options()
    assert system.statue.restitution is None  # Housner's value
    assert system.statue.friction is None  # never slides
    assert system.pedestal is None
    assert motion == rk.Harmonic(amplitude=3.0, frequency=1.5, cycles=2)
    assert duration is None  # the motion, then free motion until at rest (rk.simulate's default)


def test_simulation_options_are_passed_through():
    d = _mutated(("simulation",), {
        "duration": 3.0, "gravity": 9.81, "normal_force": "paper", "impact": "paper", "rtol": 1e-8,
        "atol": 1e-10, "max_step": 0.01, "save_dt": 0.02, "rest_velocity": 1e-5, "max_events": 500,
        "free_time_limit": 12.5, "max_samples": 1000,
    })
    _, _, options, duration = load_config(d).to_specs()
    assert duration == 3.0
    assert options == rk.Options(gravity=9.81, normal_force="paper", impact="paper", rtol=1e-8, atol=1e-10,
                                 max_step=0.01, save_dt=0.02, rest_velocity=1e-5, max_events=500,
                                 free_time_limit=12.5, max_samples=1000)


def test_friction_without_kinetic_means_equal_coefficients():
    d = _mutated(("statue", "friction"), {"static": 0.4})
    system, *_ = load_config(d).to_specs()
    assert system.statue.friction.mu_k == 0.4


@pytest.mark.parametrize(
    ("motion", "cls", "attrs"),
    [
        ({"shape": "sine", "amplitude": 2.0, "frequency": 1.0, "phase": 0.5}, rk.SinePulse,
         {"amplitude": 2.0, "frequency": 1.0, "phase": 0.5}),
        ({"shape": "cosine", "amplitude": 2.0, "frequency": 1.0}, rk.CosinePulse, {"frequency": 1.0}),
        ({"shape": "rectangle", "amplitude": -2.0, "width": 0.3}, rk.RectanglePulse, {"width": 0.3}),
        ({"shape": "ricker", "amplitude": 2.0, "frequency": 2.0, "center": 1.0}, rk.RickerPulse, {"center": 1.0}),
    ],
)
def test_pulses(motion, cls, attrs):
    _, m, _, duration = load_config(_mutated(("motion",), {"kind": "pulse", **motion})).to_specs()
    assert isinstance(m, cls)
    for k, v in attrs.items():
        assert getattr(m, k) == v
    assert duration is None


def test_harmonic_form_and_angular_frequency():
    d = _mutated(("motion",), {"kind": "harmonic", "amplitude": 6.75, "frequency": 1.2, "cycles": 30,
                               "form": "sin", "angular_frequency": 7.53})
    _, m, _, _ = load_config(d).to_specs()
    assert m.form == "sin" and m.omega == 7.53


# -------------------------------------------------------------------------- records
def test_record_scale_and_pga():
    raw = read_record(RINALDI)
    _, m, _, _ = load_config(_mutated(("motion",), {"kind": "record", "path": RINALDI, "scale": 2.0})).to_specs()
    assert m.pga == pytest.approx(2.0 * raw.pga)
    _, m, _, _ = load_config(_mutated(("motion",), {"kind": "record", "path": RINALDI, "pga": 3.0})).to_specs()
    assert m.pga == 3.0


def test_record_by_bundled_file_name_and_case_insensitive_stem():
    for name in (f"{RINALDI}.AT2", RINALDI.lower()):
        _, m, _, _ = load_config(_mutated(("motion",), {"kind": "record", "path": name})).to_specs()
        assert m.name == RINALDI


def test_relative_record_path_is_resolved_against_the_config_folder(tmp_path, monkeypatch):
    folder = tmp_path / "study"
    (folder / "records").mkdir(parents=True)
    shutil.copy(bundled_records()[RINALDI], folder / "records" / "mine.AT2")
    cfg_file = folder / "run.toml"
    cfg_file.write_text(TOML.replace(
        'kind = "harmonic"\namplitude = 3.0\nfrequency = 1.5\ncycles = 2',
        'kind = "record"\npath = "records/mine.AT2"\nscale = 0.5',
    ), encoding="utf-8")
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    monkeypatch.chdir(elsewhere)  # the current directory must not matter
    cfg = load_config(cfg_file)
    assert cfg.record_file() == (folder / "records" / "mine.AT2").resolve()
    _, m, _, _ = cfg.to_specs()
    assert m.pga == pytest.approx(0.5 * read_record(RINALDI).pga)


def test_current_directory_is_not_searched_for_records(tmp_path, monkeypatch):
    shutil.copy(bundled_records()[RINALDI], tmp_path / "local.AT2")
    cfg_dir = tmp_path / "cfg"
    cfg_dir.mkdir()
    cfg_file = cfg_dir / "run.toml"
    cfg_file.write_text(TOML.replace(
        'kind = "harmonic"\namplitude = 3.0\nfrequency = 1.5\ncycles = 2',
        'kind = "record"\npath = "local.AT2"',
    ), encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    with pytest.raises(ConfigError, match=r"motion\.path: record not found"):
        load_config(cfg_file)


def test_dict_record_paths_are_relative_to_base_dir(tmp_path):
    shutil.copy(bundled_records()[RINALDI], tmp_path / "r.AT2")
    d = _mutated(("motion",), {"kind": "record", "path": "r.AT2"})
    cfg = load_config(d, base_dir=tmp_path)
    assert cfg.record_file() == (tmp_path / "r.AT2").resolve()


def test_record_error_passes_through_with_file_and_line(tmp_path):
    rec = tmp_path / "broken.AT2"
    rec.write_text("title\nevent\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS= 3, DT= 0.01 SEC\n0.1 0.2 oops\n")
    cfg_file = tmp_path / "run.toml"
    cfg_file.write_text(TOML.replace(
        'kind = "harmonic"\namplitude = 3.0\nfrequency = 1.5\ncycles = 2',
        'kind = "record"\npath = "broken.AT2"',
    ), encoding="utf-8")
    with pytest.raises(ConfigError) as info:
        load_config(cfg_file)
    msg = str(info.value)
    assert msg.startswith(f"{cfg_file}: motion.path: ")
    assert f"{rec}: line 5: cannot parse 'oops'" in msg
    assert info.value.field == "motion.path"


# --------------------------------------------------------------------------- errors
@pytest.mark.parametrize(("old", "new", "field", "words"), [c[1:] for c in BAD_TOML], ids=[c[0] for c in BAD_TOML])
def test_bad_toml_names_file_and_field(tmp_path, old, new, field, words):
    f = tmp_path / "bad.toml"
    f.write_text(_bad_toml_text(old, new), encoding="utf-8")
    with pytest.raises(ConfigError) as info:
        load_config(f)
    err = info.value
    msg = str(err)
    assert isinstance(err, ValueError)
    assert msg.startswith(f"{f}: {field}: "), msg
    assert words in msg
    assert "\n" not in msg
    assert err.source == str(f) and err.field == field


def test_contract_example_message(tmp_path):
    f = tmp_path / "c.toml"
    f.write_text(TOML.replace("width = 0.3", "width = -1"), encoding="utf-8")
    with pytest.raises(ConfigError, match=r"statue\.width: must be > 0, got -1$"):
        load_config(f)


def test_unknown_key_suggests_the_right_one():
    with pytest.raises(ConfigError, match=r"statue\.widht: unknown key; did you mean 'width'\?"):
        load_config(_mutated(("statue", "widht"), 0.3))


def test_unknown_bundled_record_suggests_close_names():
    with pytest.raises(ConfigError, match=RINALDI):
        load_config(_mutated(("motion",), {"kind": "record", "path": RINALDI[:-1]}))


def test_all_problems_are_reported_on_one_line():
    d = _mutated(("statue", "width"), -1)
    d["statue"]["height"] = 0
    with pytest.raises(ConfigError) as info:
        load_config(d)
    assert [f for f, _ in info.value.problems] == ["statue.width", "statue.height"]
    assert "\n" not in str(info.value)


def test_dict_errors_have_no_file_prefix():
    with pytest.raises(ConfigError, match=r"^statue\.mass: missing"):
        load_config(_mutated(("statue", "mass"), None, delete=True))


def test_missing_file_and_directory(tmp_path):
    with pytest.raises(ConfigError, match=r"nope\.toml: no such file"):
        load_config(tmp_path / "nope.toml")
    with pytest.raises(ConfigError, match="is a directory"):
        load_config(tmp_path)


def test_invalid_toml_names_file_and_line(tmp_path):
    f = tmp_path / "broken.toml"
    f.write_text("[statue]\nwidth = = 3\n", encoding="utf-8")
    with pytest.raises(ConfigError, match=r"broken\.toml: invalid TOML: .*line 2"):
        load_config(f)


def test_not_a_config_type():
    with pytest.raises(ConfigError, match="TOML path or a dict"):
        load_config(42)  # type: ignore[arg-type]


def test_config_is_immutable_and_passes_through_load():
    cfg = load_config(BASE)
    assert load_config(cfg) is cfg
    assert isinstance(cfg, Config)
    with pytest.raises(Exception):
        cfg.statue.width = 2.0  # type: ignore[misc]


def test_config_error_survives_pickling():
    import pickle

    err = ConfigError([("statue.width", "must be > 0, got -1")], "c.toml")
    back = pickle.loads(pickle.dumps(err))
    assert str(back) == str(err) and back.field == "statue.width" and back.source == "c.toml"


CONTRACT = """\
[statue]                  # the block that rocks
width = 0.3               # m, B
height = 1.2              # m, H
mass = 100.0              # kg
restitution = 0.8         # optional; omitted = Housner's value
friction = { static = 0.5, kinetic = 0.4 }   # optional, on what it stands on
[pedestal]                # optional
mass = 50.0
friction = { static = 0.2, kinetic = 0.15 }
[motion]
kind = "harmonic"
amplitude = 6.75          # m/s²
frequency = 1.2           # Hz
cycles = 30
form = "cos"              # or "sin"
[simulation]
duration = 25.0           # s; default: the motion's duration
gravity = 9.81            # m/s²; default 9.80665
normal_force = "full"     # or "paper"
impact = "coulomb"        # or "paper"
"""


def test_the_documented_contract_file_parses(tmp_path):
    f = tmp_path / "contract.toml"
    f.write_text(CONTRACT, encoding="utf-8")
    system, motion, options, duration = load_config(f).to_specs()
    assert system.statue.restitution == 0.8 and system.top_friction.static == 0.5
    assert system.floor_friction.kinetic == 0.15
    assert motion.cycles == 30 and options.gravity == 9.81 and duration == 25.0


def test_record_with_units_and_format_overrides():
    d = _mutated(("motion",), {"kind": "record", "path": RINALDI, "units": "g", "format": "peer", "pga": 2.0})
    _, m, _, _ = load_config(d).to_specs()
    assert m.pga == 2.0 and m.meta["format"] == "peer"
    # units that contradict the header ("IN UNITS OF G") win only with units_override
    with pytest.raises(ConfigError, match="motion.units: .* units_override = true"):
        load_config(_mutated(("motion",), {"kind": "record", "path": RINALDI, "units": "cm/s2"}))
    _, m2, _, _ = load_config(_mutated(("motion",), {"kind": "record", "path": RINALDI, "units": "cm/s2",
                                                     "units_override": True})).to_specs()
    assert m2.pga == pytest.approx(read_record(RINALDI).pga / 9.80665 * 0.01)


def test_vertical_component_from_a_second_record(tmp_path):
    """A vertical record with the same samples is attached and scaled with the horizontal one."""
    import numpy as np

    from rocking.io.config import ConfigError, load_config

    t = np.arange(0, 2.0, 0.01)
    (tmp_path / "h.txt").write_text("Time[s] Accel[g]\n" + "\n".join(f"{x:.2f} {0.3*np.sin(6*x):.6f}" for x in t))
    (tmp_path / "v.txt").write_text("Time[s] Accel[g]\n" + "\n".join(f"{x:.2f} {0.1*np.cos(9*x):.6f}" for x in t))
    (tmp_path / "v_short.txt").write_text("Time[s] Accel[g]\n" + "\n".join(f"{x:.2f} 0.0" for x in t[:50]))
    base = {"statue": {"width": 0.3, "height": 1.2, "mass": 10.0},
            "motion": {"kind": "record", "path": "h.txt", "vertical_path": "v.txt", "scale": 2.0}}
    cfg = load_config(base, base_dir=tmp_path)
    _, motion, _, _ = cfg.to_specs()
    assert motion.vertical is not None
    np.testing.assert_allclose(motion.vertical_acceleration(np.array([0.5])), 2.0 * 0.1 * np.cos(4.5) * 9.80665, rtol=1e-4)  # file holds 6 decimals of g
    base["motion"]["vertical_path"] = "v_short.txt"
    with pytest.raises(ConfigError, match="motion.vertical_path.*share their samples"):
        load_config(base, base_dir=tmp_path).to_specs()
