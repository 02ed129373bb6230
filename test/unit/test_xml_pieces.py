"""A big description is parsed a piece at a time, so other threads (physics) run meanwhile."""

import threading
import time

from _arm1sim.description import safe_xml


def _big_urdf(links: int) -> str:
    pad = 'x' * 80
    body = ''.join('<link name="l%d"><visual name="%s"/></link>' % (i, pad) for i in range(links))
    return '<robot name="big">%s</robot>' % body


def _ticks_while(parse, text: str) -> int:
    """How often a thread that wakes every millisecond ran while ``parse(text)`` ran."""
    ticks, done = [0], threading.Event()

    def tick() -> None:
        while not done.is_set():
            ticks[0] += 1
            time.sleep(0.001)

    t = threading.Thread(target=tick)
    t.start()
    time.sleep(0.01)
    start = ticks[0]
    try:
        root = parse(text)
    finally:
        during = ticks[0] - start
        done.set()
        t.join()
    assert len(root) == text.count('<link ')
    return during


def test_trusted_parse_of_a_20_mb_description_lets_another_thread_run():
    text = _big_urdf(170_000)
    assert len(text) > 20e6
    # one C call (ET.fromstring) would hold the interpreter lock throughout: no tick at all
    assert _ticks_while(safe_xml.parse_trusted, text) >= 5


def test_safe_parse_of_a_20_mb_description_lets_another_thread_run():
    text = _big_urdf(170_000)
    assert _ticks_while(lambda t: safe_xml.parse(t, 'big'), text) >= 5


def test_pieces_split_anywhere_give_the_same_tree():
    text = '<robot name="r">' + '<link name="é%d"/>' % 1 * 3 + '</robot>'
    old, safe_xml.PIECE = safe_xml.PIECE, 7  # splits inside tags and a multi-byte character
    try:
        root = safe_xml.parse_trusted(text)
    finally:
        safe_xml.PIECE = old
    assert [link.get('name') for link in root] == ['é1'] * 3
