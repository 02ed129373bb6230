"""session/web_picture.py: when the docs picture may be taken (the page at real time for long
enough) and how it is shrunk."""

import io

import numpy as np
from PIL import Image

from _arm1sim.session.web_picture import optimised_png, steady_since


def test_steady_since_counts_back_to_the_last_reading_off_real_time():
    readings = [(0.0, 1.0), (1.0, 0.43), (2.0, 0.99), (3.0, None), (4.0, 1.01), (5.0, 1.0)]
    assert steady_since(readings, 0.02) == 4.0
    assert steady_since(readings[:3], 0.02) == 2.0
    assert steady_since(readings[:3], 0.6) == 0.0


def test_steady_since_is_never_when_the_last_reading_is_off():
    assert steady_since([(0.0, 1.0), (1.0, 0.97)], 0.02) == float('inf')
    assert steady_since([(0.0, 1.0), (1.0, None)], 0.02) == float('inf')
    assert steady_since([], 0.02) == float('inf')


def test_optimised_png_keeps_size_and_looks_the_same():
    rng = np.random.default_rng(0)
    rgb = np.full((120, 200, 3), 230, np.uint8)
    rgb[20:60, 30:90] = (255, 140, 0)  # a flat orange link
    rgb[70:110, 100:190] = rng.integers(0, 256, (40, 90, 3), dtype=np.uint8)  # worst case
    raw = io.BytesIO()
    Image.fromarray(rgb).save(raw, 'PNG')
    small = optimised_png(raw.getvalue())
    out = np.asarray(Image.open(io.BytesIO(small)).convert('RGB')).astype(int)
    assert out.shape == rgb.shape
    assert (out[:60] == rgb[:60]).all()  # flat colours exactly
    assert np.abs(out - rgb).mean() < 12
