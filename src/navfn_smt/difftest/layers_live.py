"""The costmap level of the live difftest: Nav2's global costmap layers, built from the user's
sources (``costmap-layers`` of an oracle build), against the model of :mod:`navfn_smt.nav2.costmap`
for the distribution the sources were detected as.

A configuration is an occupancy grid as map_server publishes it, the costmap node's
parameters and a list of layers (the static layer, then zero to two inflation layers of every
type the version has).  The two agree when the master costmap is the same byte for byte and
the footprint's inscribed and circumscribed radii are the same doubles.

Rolling's ``InflationLayer`` takes its distances' square roots with Eigen, whose result
depends on the CPU's ``rsqrtps`` (see :func:`~navfn_smt.nav2.inflation.matrix_sqrt`).  A
configuration with that layer is run with each of the model's square roots, and agrees when
one of them gives the C++'s bytes.  The summary counts which ones did (``sqrt_match``: ``all``
when the configuration does not tell them apart, else the names of those that match, ``none``
when none does), and :func:`cpu_sqrt` compares the build's own Eigen square root with each of
the model's on every integer below 2^20.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Callable, Iterator, Optional

import numpy as np

from ..nav2.costmap import (INFLATION, LEGACY_INFLATION, STATIC, CostmapParams, InflationParams, LayerSpec,
                            build_global_costmap, inflation_types)
from ..nav2.inflation import SQRT_MODES
from ..errors import NavfnInputError
from ..spec.arithmetic import LAYERS_X86_64, LayersArithmetic
from ..nav2.mapserver import MapServerMap

MAX_DETAILS = 20
OCCUPANCY = (-1, 0, 0, 0, 0, 100, 100, 100, 99, 98, 65, 50, 1, 30)
RESOLUTIONS = (0.05, 0.1, 0.025, 0.2, 1.0, 0.07)


@dataclass
class LayersConfig:
    occupancy: np.ndarray  # int8 (height, width)
    resolution: float  # as the map's YAML writes it (the grid holds its float32)
    origin: tuple
    params: CostmapParams
    name: str = ""


@dataclass
class LayersSummary:
    distribution: str
    configs: int = 0
    agreeing: int = 0
    outcomes: dict = field(default_factory=dict)  # the layer types that ran -> configurations
    sqrt_match: dict = field(default_factory=dict)  # configs with a distance-transform layer -> the variant matched
    disagreements: list = field(default_factory=list)
    cpp_seconds: float = 0.0
    model_seconds: float = 0.0
    cpu_sqrt: Optional[dict] = None  # this machine's Eigen square root against the model's (cpu_sqrt)

    def as_dict(self) -> dict:
        return {"level": "costmap", "cpu_sqrt": self.cpu_sqrt, "distribution": self.distribution, "cases": self.configs,
                "passed": self.agreeing, "failed": self.configs - self.agreeing,
                "outcomes": dict(sorted(self.outcomes.items())), "sqrt_match": dict(sorted(self.sqrt_match.items())),
                "cpp_seconds": round(self.cpp_seconds, 3), "model_seconds": round(self.model_seconds, 3),
                "disagreements": self.disagreements}


def model_costmap(cfg: LayersConfig, distro: str, sqrt: str = SQRT_MODES[0], arith: LayersArithmetic = LAYERS_X86_64):
    """The model's global costmap of ``cfg`` (:func:`~navfn_smt.nav2.costmap.build_global_costmap`
    on the grid as a map_server map of ``distro``), in the layers build's arithmetic ``arith``."""
    h, w = cfg.occupancy.shape
    m = MapServerMap(Path("generated"), Path("generated"), cfg.resolution, float(np.float32(cfg.resolution)),
                     (cfg.origin[0], cfg.origin[1], 0.0), w, h, "trinary", False, distro, 0.65, 0.25,
                     cfg.occupancy, None, None)
    return build_global_costmap(m, cfg.params, distro, sqrt=sqrt, arith=arith)


def _first_difference(model, answer) -> Optional[tuple]:
    if model.costmap.shape != answer.costmap.shape:
        return "size", list(model.costmap.shape), list(answer.costmap.shape)
    diff = np.argwhere(model.costmap != answer.costmap)
    if len(diff):
        j, i = (int(v) for v in diff[0])
        return f"cell ({i}, {j}) of {len(diff)}", int(model.costmap[j, i]), int(answer.costmap[j, i])
    for key in ("inscribed_radius", "circumscribed_radius"):
        a, b = getattr(model, key), getattr(answer, key)
        if a != b:
            return key, a.hex(), b.hex()
    return None


def compare_config(cfg: LayersConfig, oracle, summary: LayersSummary, arith: LayersArithmetic = LAYERS_X86_64) -> None:
    distro = summary.distribution
    t0 = time.perf_counter()
    answer = oracle.costmap(cfg.occupancy, cfg.resolution, cfg.origin, cfg.params)
    summary.cpp_seconds += time.perf_counter() - t0
    summary.configs += 1
    kinds = inflation_types(distro)
    ran = "static" + "".join(f" + {kinds[lay.type]}" for lay in cfg.params.plugins if lay.type in kinds)
    summary.outcomes[ran] = summary.outcomes.get(ran, 0) + 1
    has_dt = any(kinds.get(lay.type) == "current" for lay in cfg.params.plugins)
    t1 = time.perf_counter()
    diffs = {sqrt: _first_difference(model_costmap(cfg, distro, sqrt, arith), answer)
             for sqrt in (SQRT_MODES if has_dt else SQRT_MODES[:1])}
    summary.model_seconds += time.perf_counter() - t1
    matched = [sqrt for sqrt, d in diffs.items() if d is None]
    diff = None if matched else diffs[SQRT_MODES[0]]
    if has_dt:
        # "all": the configuration does not tell the square roots apart; "<names> only": the ones
        # this machine's C++ agrees with where they differ
        key = "none" if not matched else "all" if len(matched) == len(diffs) else f"{'+'.join(matched)} only"
        summary.sqrt_match[key] = summary.sqrt_match.get(key, 0) + 1
    if diff is None:
        summary.agreeing += 1
    elif len(summary.disagreements) < MAX_DETAILS:
        summary.disagreements.append({"config": cfg.name, "case": 0, "field": diff[0], "model": diff[1],
                                      "cpp": diff[2], "layers": ran, "params": repr(cfg.params),
                                      "occupancy": cfg.occupancy.tolist(), "resolution": cfg.resolution,
                                      "origin": list(cfg.origin)})


def run_layers_live(configs, oracle, progress: Optional[Callable[[int], None]] = None,
                    arith: Optional[LayersArithmetic] = None) -> LayersSummary:
    """Every configuration of ``configs`` against the layers build ``oracle``, the model in the
    arithmetic ``arith`` (None: x86-64's)."""
    summary = LayersSummary(oracle.build["distribution"])
    for cfg in configs:
        compare_config(cfg, oracle, summary, arith or LAYERS_X86_64)
        if progress:
            progress(1)
    if "eigen-sqrt" in oracle.build["programs"]:
        summary.cpu_sqrt = cpu_sqrt(oracle.folder)
    return summary


CPU_SQRT_VALUES = 1 << 20  # the squared distances (integers) of maps up to 724 cells across


def cpu_sqrt(folder) -> dict:
    """This machine's Eigen square root (the build's ``eigen-sqrt``) on the integers below
    :data:`CPU_SQRT_VALUES`, against each of the model's: how many differ, and ``sqrt(49)``."""
    from ..nav2.inflation import matrix_sqrt
    from ..oracle.client import EigenSqrt

    x = np.arange(CPU_SQRT_VALUES, dtype=np.float32)
    with EigenSqrt(folder) as e:
        got = e.sqrt(x)
    differ = {m: int(np.count_nonzero(got.view(np.uint32) != matrix_sqrt(x, m).view(np.uint32)))
              for m in SQRT_MODES}
    match = [m for m, k in differ.items() if k == 0]
    return {"values": CPU_SQRT_VALUES, "differ": differ, "sqrt_49": float(got[49]),
            "matches": match[0] if match else None}


def _inflation(rng, kind: str) -> InflationParams:
    return InflationParams(enabled=bool(rng.random() < 0.95),
                           inflation_radius=float(rng.choice([0.0, 0.1, 0.22, 0.3, 0.55, 0.7, 1.0])),
                           cost_scaling_factor=float(rng.choice([1.0, 3.0, 5.5, 10.0])),
                           inflate_unknown=bool(rng.random() < 0.3), inflate_around_unknown=bool(rng.random() < 0.3),
                           custom_inscribed_radius=float(rng.choice([-1.0, -1.0, 0.05, 0.2])) if kind == "current"
                           else -1.0)


def sqrt_probe() -> LayersConfig:
    """One lethal cell in the middle of a free 61x61 grid, inflated 30 cells out by the
    distance-transform layer: 12 of its cells get another cost from the emulated AMD Zen square
    root than from the correctly rounded one, so the configuration tells those two apart."""
    occ = np.zeros((61, 61), dtype=np.int8)
    occ[30, 30] = 100
    layers = (LayerSpec("static_layer", STATIC),
              LayerSpec("inflation_layer", INFLATION, InflationParams(inflation_radius=1.5, cost_scaling_factor=1.0)))
    return LayersConfig(occ, 0.05, (0.0, 0.0), replace(CostmapParams(), plugins=layers, robot_radius=0.0,
                                                       footprint_padding=0.0), name="sqrt probe")


def generated_configs(distro: str, count: int, seed: int = 0) -> Iterator[LayersConfig]:
    """``count`` generated configurations for ``distro`` (seeded); with a distance-transform
    layer in the version, the first is :func:`sqrt_probe`."""
    rng = np.random.default_rng(seed)
    types = [t for t in (INFLATION, LEGACY_INFLATION) if t in inflation_types(distro)]
    if count > 0 and inflation_types(distro).get(INFLATION) == "current":
        count -= 1
        yield sqrt_probe()
    for c in range(count):
        w, h = int(rng.integers(1, 41)), int(rng.integers(1, 41))
        occ = rng.choice(np.array(OCCUPANCY, dtype=np.int8), size=(h, w))
        res = float(rng.choice(RESOLUTIONS))
        origin = (float(rng.choice([0.0, -1.5, 0.3, -w * res / 2])), float(rng.choice([0.0, 2.0, -h * res / 2])))
        layers = [LayerSpec("static_layer", STATIC)]
        for k in range(int(rng.integers(0, 3))):
            t = types[int(rng.integers(len(types)))]
            layers.append(LayerSpec(f"inflation_{k}", t, _inflation(rng, inflation_types(distro)[t])))
        params = replace(CostmapParams(), plugins=tuple(layers), robot_radius=float(rng.choice([0.05, 0.1, 0.22, 0.3])),
                         footprint_padding=float(rng.choice([0.0, 0.01, 0.03])),
                         track_unknown_space=bool(rng.random() < 0.6),
                         lethal_cost_threshold=int(rng.choice([100, 100, 65, 50, 0, 120, -5, 2**32 + 50,
                                                               2**31 + 50])),
                         trinary_costmap=bool(rng.random() < 0.7),
                         unknown_cost_value=int(rng.choice([255, 255, 0, 99, 511, -1])),
                         inscribed_obstacle_cost_value=int(rng.choice([99, 99, 98, 50, 355, -157])),
                         use_maximum=bool(rng.random() < 0.3))
        yield LayersConfig(occ, res, origin, params, name=f"seed {seed} config {c}")


def map_config(map_yaml, params_file, distro: str) -> tuple[LayersConfig, list]:
    """A user's map_server map and params file (its global costmap section; nav2_bringup's when
    none is given) as one configuration: the static and inflation layers of the file, in order;
    the notes name the layers left out (they need sensor data or filter masks)."""
    from ..nav2.costmap import bringup_params, load_costmap_params
    from ..nav2.mapserver import load_map_yaml
    from ..oracle.client import LAYER_KINDS

    m = load_map_yaml(Path(map_yaml), distro=distro)
    params = load_costmap_params(params_file, distro) if params_file else bringup_params(distro)
    if params.footprint.strip() not in ("", "[]"):
        raise NavfnInputError(f"{params_file}: a footprint polygon is not passed to the C++ layers (the driver makes "
                              f"the footprint from robot_radius); compare with robot_radius instead")
    kept = tuple(lay for lay in params.plugins if lay.type in LAYER_KINDS)
    notes = [f"{lay.name} ({lay.type}) left out: not a static or inflation layer" for lay in params.plugins
             if lay.type not in LAYER_KINDS]
    return LayersConfig(m.occupancy, m.resolution, (m.origin[0], m.origin[1]), replace(params, plugins=kept),
                        name=str(map_yaml)), notes
