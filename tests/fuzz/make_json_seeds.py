#!/usr/bin/env python3
"""Writes the deep and long seed inputs of the JSON fuzz targets (tests/fuzz/README.md):
corpus/ (capture reader, JSON-only inputs), corpus-expectations/ and corpus-timing/, and the
regression inputs that once crashed or hung aoreplay (issue 20) into the regression folders.
Usage: python3 tests/fuzz/make_json_seeds.py   (from anywhere; rewrites the files it owns)"""
import json
import os

here = os.path.dirname(os.path.abspath(__file__))
identity = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -2, 1]
projection = [1.299038, 0, 0, 0, 0, 1.732051, 0, 0, 0, 0, -1.001001, -1, 0, 0, -0.1001001, 0]


def write(folder, name, text):
    os.makedirs(os.path.join(here, folder), exist_ok=True)
    with open(os.path.join(here, folder, name), "w", encoding="utf-8") as f:
        f.write(text)


def nested(depth, leaf="1"):
    """depth arrays inside each other around leaf"""
    return "[" * depth + leaf + "]" * depth


def nested_objects(depth, leaf="1"):
    return '{"a":' * depth + leaf + "}" * depth


def capture(frames=1, scene="{}", extra=""):
    frame = json.dumps({"gbuffer": "frames/0000.exr", "view": identity, "projection": projection})
    return ('{"format": "aoreplay-capture", "version": 1, "width": 4, "height": 3, %s"scene": %s, "frames": [%s]}'
            % (extra, scene, ", ".join([frame] * frames)))


# capture.json (no EXR part: the reader stops at the missing file, after all JSON checks)
write("corpus", "seed-deep-scene-over-limit", capture(scene='{"a": %s}' % nested_objects(130)))
write("corpus", "seed-deep-scene-at-limit", capture(scene='{"a": %s}' % nested(125)))
write("corpus", "seed-long-unknown-key", capture(extra='"%s": 1, ' % ("k" * 65536)))
write("corpus", "seed-long-path", capture().replace("frames/0000.exr", "frames/" + "p" * 8192 + ".exr"))
write("corpus", "seed-200-frames", capture(frames=200))
write("corpus", "seed-radius-overflow", capture(scene='{"ao_radius": 1e300}'))
write("corpus", "seed-radius-underflow", capture(scene='{"ao_radius": 1e-300}'))
write("corpus", "seed-duplicate-nested-key", capture(scene='{"a": {"b": 1, "b": 2}}'))
write("corpus", "seed-big-integer", capture().replace('"width": 4', '"width": 18446744073709551616'))

# --expect files
valid = {"max": {"error.rmse": 0.1, "gpu_ms.gtao": 5, "temporal.disocclusion.response_frames": 6},
         "min": {"error.rmse": 0.01}}
write("corpus-expectations", "seed-valid", json.dumps(valid, indent=2))
write("corpus-expectations", "seed-deep", '{"max": {"error.rmse": %s}}' % nested(200))
write("corpus-expectations", "seed-deep-objects", '{"max": %s}' % nested_objects(200))
write("corpus-expectations", "seed-long-metric", '{"max": {"%s": 1}}' % ("m" * 65536))
write("corpus-expectations", "seed-duplicate", '{"max": {"error.rmse": 0.1}, "max": {"error.rmse": 1}}')
write("corpus-expectations", "seed-numbers", '{"max": {"error.rmse": 1e308, "gpu_ms.gtao": -0, "error.max": 1e-400}}')

# compare inputs: report.json and Google Benchmark JSON
samples = [1.0, 1.1, 0.9, 1.05, 0.95]
report = {"tool": "aoreplay", "passes": [{"name": n, "gpu_ms": {"samples": samples}} for n in ("upload", "gtao", "spatial")]}
bench = {"context": {}, "benchmarks": [
    {"name": "gtao/64x36/repeats:5", "run_name": "gtao/64x36", "run_type": "iteration", "real_time": 1000 + i,
     "time_unit": "us"} for i in range(5)] + [{"name": "gtao/64x36_median", "run_type": "aggregate", "real_time": 1}]}
write("corpus-timing", "seed-report", json.dumps(report, indent=1))
write("corpus-timing", "seed-benchmark", json.dumps(bench, indent=1))
write("corpus-timing", "seed-mistyped", json.dumps({"benchmarks": [{"name": 5, "run_type": 1, "time_unit": True}]}))
write("corpus-timing", "seed-long-name",
      json.dumps({"tool": "aoreplay", "passes": [{"name": "x" * 50000, "gpu_ms": {"samples": samples}}]}))
write("corpus-timing", "seed-deep", '{"tool": "aoreplay", "passes": %s}' % nested(200))

# Inputs that crashed aoreplay before issue 20 (stack overflow in nlohmann's recursive functions).
write("regression", "issue20-scene-60000-deep", capture(scene='{"a": %s}' % nested(60000)))
write("regression-expectations", "issue20-expect-60000-deep", '{"max": {"error.rmse": %s}}' % nested(60000))
write("regression-timing", "issue20-report-60000-deep", '{"tool": "aoreplay", "passes": %s}' % nested(60000))
