"""render releases the GIL, calls progress on the calling thread, stops on
Ctrl-C within half a second, and does not leak memory over many renders."""
from __future__ import annotations

import json
import queue
import signal
import subprocess
import threading
import time

import numpy as np
import pytest

import holoray
from conftest import THREADS
from helpers import vm_rss_bytes

PYTHON = "/usr/bin/python3"


def test_other_python_threads_run_during_a_render(primitives):
    camera = holoray.LensArray(lenses=(128, 128), pixels_per_lens=8)  # 1024x1024
    ticks: list[float] = []
    stop = threading.Event()

    def ticker():
        while not stop.is_set():
            ticks.append(time.monotonic())
            time.sleep(0.001)

    thread = threading.Thread(target=ticker)
    thread.start()
    try:
        time.sleep(0.05)
        start = time.monotonic()
        holoray.render(primitives, camera, threads=1)  # one worker: the other core is free for the ticker
        end = time.monotonic()
    finally:
        stop.set()
        thread.join()
    duration = end - start
    assert duration > 0.1, f"the render took only {duration:.3f} s: too short to tell"
    inside = [t for t in ticks if start + 0.02 < t < end - 0.02]
    # A thread blocked on the GIL would tick at most a few times; at 1 ms a
    # tick a free one ticks hundreds of times.
    expected = (duration - 0.04) / 0.001
    assert len(inside) >= max(20, 0.2 * expected), f"{len(inside)} ticks during a {duration:.3f} s render"


def test_progress_is_called_on_the_calling_thread_with_increasing_fractions(primitives):
    calls: list[tuple[int, float]] = []
    caller = threading.get_ident()
    holoray.render(primitives, holoray.LensArray(lenses=(96, 96), pixels_per_lens=8), threads=THREADS,
                   progress=lambda f: calls.append((threading.get_ident(), f)))
    assert calls, "progress was never called"
    assert {ident for ident, _ in calls} == {caller}
    fractions = [f for _, f in calls]
    assert all(0.0 <= f <= 1.0 for f in fractions), fractions
    assert all(b >= a for a, b in zip(fractions, fractions[1:])), fractions
    assert fractions[-1] == 1.0


def test_progress_is_called_from_a_render_on_a_worker_thread(primitives):
    # The calling thread need not be the main thread.
    calls, errors = [], []

    def work():
        try:
            caller = threading.get_ident()
            holoray.render(primitives, holoray.LensArray(lenses=(32, 32), pixels_per_lens=4), threads=THREADS,
                           progress=lambda f: calls.append((threading.get_ident() == caller, f)))
        except BaseException as e:  # noqa: BLE001 - reported below
            errors.append(e)

    t = threading.Thread(target=work)
    t.start()
    t.join(60)
    assert not errors, errors
    assert calls and all(same for same, _ in calls)
    assert calls[-1][1] == 1.0


def test_an_exception_in_progress_ends_the_render_with_it(primitives):
    class Stop(Exception):
        pass

    def progress(f):
        raise Stop()

    with pytest.raises(Stop):
        holoray.render(primitives, holoray.LensArray(lenses=(64, 64), pixels_per_lens=8), threads=THREADS,
                       progress=progress)


CHILD = r"""
import json, os, signal, sys, threading, time
import holoray

def cpu_seconds():
    with open('/proc/self/stat') as f:
        fields = f.read().rsplit(')', 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf('SC_CLK_TCK')   # utime + stime

def os_threads():
    return len(os.listdir('/proc/self/task'))

scene = holoray.load_scene(sys.argv[1])
camera = holoray.LensArray(lenses=(256, 256), pixels_per_lens=8)   # 2048x2048
info = {'os_threads_before': os_threads()}
handled = []

def on_sigint(signum, frame):
    handled.append(time.monotonic())
    raise KeyboardInterrupt

signal.signal(signal.SIGINT, on_sigint)
progressed = []

def progress(fraction):
    if not progressed:
        print('PROGRESS %r' % fraction, flush=True)
    progressed.append(fraction)

print('STARTED', flush=True)
try:
    holoray.render(scene, camera, spp=8, progress=progress)   # some 10 s on 2 cores when not stopped
except KeyboardInterrupt:
    info['caught'] = time.monotonic()
    info['handled'] = handled[0] if handled else None
    info['python_threads'] = threading.active_count()
    info['os_threads_after'] = os_threads()
    c0 = cpu_seconds()
    time.sleep(0.3)
    info['cpu_seconds_in_next_0.3s'] = cpu_seconds() - c0
    info['last_fraction'] = progressed[-1] if progressed else None
    info['exiting'] = time.monotonic()
    print('RESULT ' + json.dumps(info), flush=True)
    raise
print('FINISHED', flush=True)
"""


def _reader(stream, q):
    for line in stream:
        q.put((time.monotonic(), line.rstrip("\n")))
    q.put((time.monotonic(), None))


def _wait_for(q, prefix, deadline, seen):
    while True:
        remaining = deadline - time.monotonic()
        if remaining <= 0:
            pytest.fail(f"no {prefix!r} line in time; output so far: {seen}")
        try:
            t, line = q.get(timeout=remaining)
        except queue.Empty:
            continue
        if line is None:
            pytest.fail(f"the child ended before {prefix!r}; output: {seen}")
        seen.append(line)
        if line.startswith(prefix):
            return t, line


def test_keyboard_interrupt_ends_a_2048_render_within_half_a_second(python_env, primitives_path):
    proc = subprocess.Popen([PYTHON, "-c", CHILD, str(primitives_path)], env=python_env, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    lines: queue.Queue = queue.Queue()
    reader = threading.Thread(target=_reader, args=(proc.stdout, lines), daemon=True)
    reader.start()
    seen: list[str] = []
    try:
        started, _ = _wait_for(lines, "STARTED", time.monotonic() + 60, seen)
        _wait_for(lines, "PROGRESS", time.monotonic() + 30, seen)
        time.sleep(max(0.0, started + 1.0 - time.monotonic()))
        assert proc.poll() is None, f"the child ended before the interrupt: {seen}"
        sent = time.monotonic()
        proc.send_signal(signal.SIGINT)
        _, result_line = _wait_for(lines, "RESULT", sent + 30, seen)
        proc.wait(timeout=30)
        exited = time.monotonic()
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    stderr = proc.stderr.read()
    assert not any(l.startswith("FINISHED") for l in seen), "the render ran to the end"
    info = json.loads(result_line[len("RESULT "):])
    assert info["handled"] is not None, "our SIGINT handler never ran"
    # CLOCK_MONOTONIC is one clock for the whole machine: the child's times compare with ours.
    latency = info["caught"] - sent
    assert latency < 0.5, f"KeyboardInterrupt reached the caller {latency:.3f} s after SIGINT ({info})"
    assert info["handled"] - sent < 0.5, info
    assert info["last_fraction"] is None or info["last_fraction"] < 1.0, "the render had finished"
    # After the exception no worker is still tracing, and no Python thread was left behind.
    assert info["python_threads"] == 1, info
    assert info["cpu_seconds_in_next_0.3s"] < 0.06, f"the process kept computing after the interrupt: {info}"
    # The process then ends promptly with the KeyboardInterrupt (no worker holds it up).
    assert exited - info["exiting"] < 1.0, f"the process took {exited - info['exiting']:.3f} s to exit"
    assert proc.returncode != 0
    assert "KeyboardInterrupt" in stderr, stderr


def _tiny_scene():
    scene = holoray.Scene()
    vertices = np.array([(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], dtype=np.float64)
    scene.add_mesh(vertices, np.array([(0, 1, 2), (0, 2, 3)]), colour=(0.5, 0.6, 0.7))
    scene.add_sphere((0, 0, 0.5), 0.4)
    scene.add_light((2, -3, 4))
    scene.set_viewpoint((0, -4, 3), (0, 0, 0), (0, 0, 1), 40)
    return scene


def test_a_thousand_small_renders_do_not_grow_memory():
    camera = holoray.LensArray(lenses=(4, 4), pixels_per_lens=4)
    calls = [0]

    def progress(fraction):
        calls[0] += 1

    def one_round(scene):
        result = holoray.render(scene, camera, threads=THREADS, aovs=("albedo", "depth", "normal", "id"),
                                progress=progress)
        assert result.colour.shape == (16, 16, 3)
        return result

    shared = _tiny_scene()
    for i in range(100):  # warm-up: allocator pools, thread pools, caches
        one_round(shared if i % 2 else _tiny_scene())
    before = vm_rss_bytes()
    start = time.monotonic()
    for i in range(1000):
        one_round(shared if i % 2 else _tiny_scene())  # a reused scene and a fresh one in turn
    after = vm_rss_bytes()
    elapsed = time.monotonic() - start
    growth = after - before
    assert calls[0] >= 1100
    assert growth < 8 * 2**20, f"VmRSS grew {growth / 2**20:.1f} MiB over 1000 renders ({elapsed:.1f} s)"


def test_results_outlive_their_scene_and_renders():
    scene = _tiny_scene()
    result = holoray.render(scene, holoray.LensArray(lenses=(4, 4), pixels_per_lens=4), threads=THREADS,
                            aovs=("depth",))
    colour, depth = result.colour, result.aovs["depth"]
    expected_colour, expected_depth = colour.copy(), depth.copy()
    del scene, result
    for _ in range(20):
        holoray.render(_tiny_scene(), holoray.LensArray(lenses=(4, 4), pixels_per_lens=4), threads=THREADS,
                       aovs=("depth",))
    np.testing.assert_array_equal(colour, expected_colour)
    np.testing.assert_array_equal(depth, expected_depth)
