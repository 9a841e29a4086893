"""Shared set-ups of the campaign tests: the synthetic grain and sensor, and a real browser.

The browser is Debian's ``chromium``, driven through the DevTools protocol over a pipe
(``--remote-debugging-pipe``: NUL-terminated JSON on file descriptors 3 and 4), so no
WebSocket library is needed. Every console message of level error, every uncaught
exception and every browser log entry of level error (a resource that failed to load)
is collected; the page's text and chosen elements are read back after the load event.
The DevTools protocol was chosen over ``--enable-logging=stderr``, whose console lines
are a log format with no contract and miss failed resource loads on ``file://`` pages.
"""

import json
import os
import select
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import contactlab as cl
from contactlab.config import load_config

ROOT = Path(__file__).resolve().parents[3]
CHROMIUM = "/usr/bin/chromium"
CHROMIUM_FLAGS = (
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--remote-debugging-pipe",
)
REQUIRE_BROWSER = os.environ.get("CONTACTLAB_REQUIRE_BROWSER") == "1"
"""Set by ``.ci/run`` (which installs chromium): a missing browser fails instead of
skipping."""


@pytest.fixture(scope="session")
def hard_setup():
    """A hard grain whose raw signal overstates the peak force by 38 %.

    The grain and the 40 kHz sensor of ``data/traces/model_hard.toml`` with a linear
    contact k2 = 4e4 N/m, c2 = 0.5 N*s/m: contact time 100 us, raw peak +38 %.
    """
    config = load_config(ROOT / "data" / "traces" / "model_hard.toml")
    law = cl.laws.LinearViscoelastic(stiffness=4e4, damping=0.5)
    return config.grain, config.sensor, law


SENSITIVITY = 0.01124
"""Sensitivity of the synthetic volt records [V/N] (as data/traces)."""

NOISE = 0.03
"""Noise of the synthetic records [N]: about 1 % of the hard grain's 3 N peaks."""

RECORDS = (
    # file, writer, writer options, law, sample rate [Hz], noise [N], in volts
    ("hard_generic.csv", "generic", {}, "hard", 2e6, NOISE, True),
    ("hard_rigol.csv", "rigol-sequence", {}, "hard", 5e6, NOISE, True),
    ("hard_keysight.csv", "keysight", {}, "hard", 1e6, 2 * NOISE, True),
    ("hard_daq.h5", "hdf5", {"name": "day1/sensor", "time": "attrs"}, "hard", 2e6, NOISE, True),
    ("hard_daq.tdms", "tdms", {"group": "day1", "channel": "sensor"}, "hard", 2e6, NOISE, False),
    ("soft.csv", "generic", {}, "soft", 2e6, NOISE / 2, False),
    ("hertz.h5", "hdf5", {"name": "day1/sensor"}, "hertz", 2e6, NOISE, True),
)
"""The good records of the shared campaign: five formats of the hard grain, with
different sample rates and noise, plus a soft linear grain and a damped-Hertz grain."""

IMPACTS_PER_RECORD = 3


def _laws(hard_law):
    soft = load_config(ROOT / "data" / "traces" / "model_soft.toml").law
    hertz = load_config(ROOT / "data" / "traces" / "model_hertz.toml").law
    return {"hard": hard_law, "soft": soft, "hertz": hertz}


@pytest.fixture(scope="session")
def campaign(tmp_path_factory, hard_setup):
    """One campaign over good and bad files, run once for the tests that read it.

    Returns a dict: ``result`` (CampaignResult), ``truth`` (file name -> truth table),
    ``folder``, ``out`` (the output folder), ``bad`` (file or path -> expected status).
    """
    from dem_check import write_trace
    from dem_check.campaign import run_campaign, synthetic_record

    grain, sensor, hard_law = hard_setup
    laws = _laws(hard_law)
    folder = tmp_path_factory.mktemp("day1")
    rng = np.random.default_rng(14)
    truth, sensitivities, metadata = {}, {}, []
    for k, (name, layout, options, law, rate, noise, volts) in enumerate(RECORDS):
        onsets = 1e-3 + np.cumsum(rng.uniform(2.5e-3, 4e-3, IMPACTS_PER_RECORD))
        velocities = rng.uniform(1.5, 2.5, IMPACTS_PER_RECORD)
        trace, table = synthetic_record(
            grain,
            sensor,
            laws[law],
            velocities,
            onsets,
            length=onsets[-1] + 2.5e-3,
            sample_rate=rate,
            noise=noise,
            sensitivity=SENSITIVITY if volts else None,
            offset=0.004 if volts else -0.05,
            seed=k,
        )
        write_trace(folder / name, trace, layout, **options)
        truth[name] = table
        if volts:
            sensitivities[name] = SENSITIVITY
        if law == "hard":  # the others get no metadata row: a note says so
            metadata += [
                {"file": name, "impact": i, "velocity [m/s]": v} for i, v in enumerate(velocities)
            ]
    # bad inputs: each must be listed with its reason while the others are analysed
    (folder / "notes.bin").write_bytes(bytes(range(256)) * 4)
    volts_without, _ = synthetic_record(
        grain,
        sensor,
        hard_law,
        [2.0],
        [1e-3],
        length=4e-3,
        sample_rate=1e6,
        noise=NOISE,
        sensitivity=SENSITIVITY,
        seed=99,
    )
    write_trace(folder / "scope2.csv", volts_without, "generic")
    quiet, _ = synthetic_record(
        grain, sensor, hard_law, [], [], length=5e-3, sample_rate=1e6, noise=NOISE, seed=98
    )
    write_trace(folder / "quiet.csv", quiet, "generic")
    empty = tmp_path_factory.mktemp("empty")
    meta_path = tmp_path_factory.mktemp("meta") / "metadata.csv"
    metadata.append({"file": "day2.csv", "impact": 0, "velocity [m/s]": 2.0})  # no such record
    pd.DataFrame(metadata).to_csv(meta_path, index=False)
    out = tmp_path_factory.mktemp("report")
    result = run_campaign(
        [folder, empty],
        sensor,
        grain,
        sensitivity=sensitivities,
        out=out,
        metadata=meta_path,
    )
    bad = {
        str(folder / "notes.bin"): "unreadable",
        str(folder / "scope2.csv"): "no sensitivity",
        str(folder / "quiet.csv"): "no impact",
        str(empty): "empty folder",
    }
    return {"result": result, "truth": truth, "folder": folder, "out": out, "bad": bad}


class DevTools:
    """A headless Chromium driven over the DevTools pipe."""

    def __init__(self, profile):
        to_child_r, self._to_child = os.pipe()
        self._from_child, from_child_w = os.pipe()
        # the browser reads commands on fd 3 and writes replies on fd 4
        redirect = f'exec 3<&{to_child_r} 4>&{from_child_w}; exec "$0" "$@"'
        self.stderr = tempfile.TemporaryFile()
        self.process = subprocess.Popen(
            ["bash", "-c", redirect, CHROMIUM, *CHROMIUM_FLAGS, f"--user-data-dir={profile}"],
            pass_fds=(to_child_r, from_child_w),
            stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL,
            stderr=self.stderr,
        )
        os.close(to_child_r)
        os.close(from_child_w)
        self._buffer, self._next_id, self.events = b"", 0, []

    def _read_message(self, deadline):
        while b"\0" not in self._buffer:
            left = deadline - time.monotonic()
            if left <= 0 or not select.select([self._from_child], [], [], left)[0]:
                raise TimeoutError("chromium did not answer in time")
            chunk = os.read(self._from_child, 1 << 16)
            if not chunk:
                raise RuntimeError("chromium closed the DevTools pipe")
            self._buffer += chunk
        message, self._buffer = self._buffer.split(b"\0", 1)
        return json.loads(message)

    def call(self, method, session=None, timeout=30.0, **params):
        """Send a command; return its result (events arriving meanwhile are kept)."""
        self._next_id += 1
        message = {"id": self._next_id, "method": method, "params": params}
        if session:
            message["sessionId"] = session
        os.write(self._to_child, json.dumps(message).encode() + b"\0")
        deadline = time.monotonic() + timeout
        while True:
            reply = self._read_message(deadline)
            if reply.get("id") == self._next_id:
                if "error" in reply:
                    raise RuntimeError(f"{method}: {reply['error']}")
                return reply["result"]
            self.events.append(reply)

    def wait_for(self, method, timeout=30.0):
        """Read events until ``method`` arrives."""
        deadline = time.monotonic() + timeout
        while not any(e.get("method") == method for e in self.events):
            self.events.append(self._read_message(deadline))

    def drain(self, quiet=0.5):
        """Keep reading events until none arrives for ``quiet`` seconds."""
        while True:
            try:
                self.events.append(self._read_message(time.monotonic() + quiet))
            except TimeoutError:
                return

    def close(self):
        try:
            self.call("Browser.close", timeout=10.0)
        except (TimeoutError, RuntimeError, OSError):
            pass
        try:
            self.process.wait(timeout=10.0)
        except subprocess.TimeoutExpired:
            self.process.kill()
            self.process.wait()
        os.close(self._to_child)
        os.close(self._from_child)
        self.stderr.close()


def _errors(events):
    """Console errors, uncaught exceptions and error log entries, as text."""
    found = []
    for event in events:
        method, params = event.get("method"), event.get("params", {})
        if method == "Runtime.consoleAPICalled" and params["type"] in ("error", "assert"):
            found.append("console: " + " ".join(str(a.get("value")) for a in params["args"]))
        elif method == "Runtime.exceptionThrown":
            found.append("exception: " + params["exceptionDetails"].get("text", ""))
        elif method == "Log.entryAdded" and params["entry"]["level"] == "error":
            entry = params["entry"]
            found.append(f"log ({entry['source']}): {entry['text']} {entry.get('url', '')}")
    return found


READ_PAGE = """JSON.stringify({
  text: document.body.innerText,
  ids: Object.fromEntries([...document.querySelectorAll('[id]')].map(e => [e.id, e.innerText])),
  idCount: document.querySelectorAll('[id]').length,
  uniqueIds: new Set([...document.querySelectorAll('[id]')].map(e => e.id)).size,
  svgs: document.querySelectorAll('svg').length,
  drawn: [...document.querySelectorAll('svg')]
    .filter(s => s.getBoundingClientRect().width > 0).length,
  scripts: document.scripts.length,
  resources: performance.getEntriesByType('resource').map(r => r.name)
})"""


@pytest.fixture(scope="session")
def open_in_chromium(tmp_path_factory):
    """``open(path) -> dict``: load an HTML file in headless Chromium and report
    ``errors`` (list of str), ``text``, ``ids`` (element id -> text), ``idCount`` and
    ``uniqueIds`` (elements with an id, and distinct ids), ``svgs`` and
    ``drawn`` (SVG elements, and those laid out with a width), ``scripts`` and
    ``resources`` (URLs the page fetched)."""
    if not os.access(CHROMIUM, os.X_OK):
        message = f"{CHROMIUM} not installed (bash .ci/run installs Debian's chromium)"
        if REQUIRE_BROWSER:
            pytest.fail(message)
        pytest.skip(message)

    def open_page(path):
        profile = tmp_path_factory.mktemp("chromium-profile")
        browser = DevTools(profile)
        try:
            targets = browser.call("Target.getTargets")["targetInfos"]
            page = next(t for t in targets if t["type"] == "page")
            session = browser.call("Target.attachToTarget", targetId=page["targetId"], flatten=True)
            session = session["sessionId"]
            for domain in ("Runtime", "Log", "Page"):
                browser.call(f"{domain}.enable", session)
            browser.call("Page.navigate", session, url=Path(path).resolve().as_uri())
            browser.wait_for("Page.loadEventFired")
            browser.drain()
            page_state = browser.call(
                "Runtime.evaluate", session, expression=READ_PAGE, returnByValue=True
            )
            report = json.loads(page_state["result"]["value"])
            report["errors"] = _errors(browser.events)
            return report
        finally:
            browser.close()
            shutil.rmtree(profile, ignore_errors=True)

    return open_page
