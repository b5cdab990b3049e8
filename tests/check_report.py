#!/usr/bin/python3
"""gonio report in a real browser: headless Chromium through Selenium (Debian's chromium,
chromium-driver and python3-selenium).

Makes a small run (the quickstart at 65 536 rays, one surface per case, a dielectric case added so
that the transmission map shows), writes its report, opens it with no network, fails on any console
error, checks every view was drawn, moves the theta_i selector and checks that the maps, the
plane-of-incidence curves and the albedo marker change, switches case, and saves a screenshot.

Usage: check_report.py GONIO WORKDIR [--screenshot PNG] [--result FILE.h5]
  --result      report this file instead of making a run (e.g. the gold table's, to time it)
"""
import argparse
import json
import os
import subprocess
import sys
import time

from selenium import webdriver
from selenium.webdriver.chrome.options import Options
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.support.ui import Select, WebDriverWait


def fail(message):
    print("check_report: FAILED: " + message)
    sys.exit(1)


def make_result(gonio, work):
    out = os.path.join(work, "report_run.h5")
    cmd = [gonio, "run", "configs/quickstart.toml", "-o", out, "--overwrite", "--quiet",
           "--no-cache", "--set", "trace.rays=65536", "--set", "surface.realisations=1",
           "--set", "beam.theta_i=[0,45,70]",
           "--set", 'case.ggx_0.3.material={type = "dielectric", eta = 1.5}',
           "--set", 'case.beckmann_0.5.model.models=["l1", "smith_measured_ndf", "measured_g1", "measured", '
           '"heitz16"]']
    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    subprocess.run(cmd, check=True, cwd=here)
    # A fit of the first case, shown with it (its residual map and its parameters).
    fit = os.path.join(work, "report_fit.json")
    subprocess.run([gonio, "fit", out, "--case", "beckmann_0.5", "--model", "beckmann", "--bootstrap", "4",
                    "-o", fit, "--overwrite", "--quiet"], check=True)
    return out, fit


def browser():
    o = Options()
    o.binary_location = "/usr/bin/chromium"
    for a in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
              "--window-size=1400,1700", "--hide-scrollbars"):
        o.add_argument(a)
    o.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    return webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=o)


def console_errors(driver):
    return [e for e in driver.get_log("browser") if e.get("level") == "SEVERE"]


def drawn(driver):
    return driver.execute_script("return document.body.dataset.drawn || ''")


# A fingerprint of what a plot shows: the sum of its traces' numbers.
FINGERPRINT = """
const el = document.getElementById(arguments[0]);
if (!el || !el.data) return null;
let s = 0, n = 0;
const add = (v) => { if (typeof v === 'number' && isFinite(v)) { s += v; n += 1; } };
for (const t of el.data) {
  for (const key of ['customdata', 'y']) {
    const a = t[key];
    if (!a) continue;
    for (const row of a) { if (Array.isArray(row)) row.forEach(add); else add(row); }
  }
}
const shapes = (el.layout && el.layout.shapes) || [];
for (const sh of shapes) add(sh.x0);
return [s, n];
"""


MASKING_CONFIG = """seed = 2
[beam]
theta_i = [30, 75]
phi_i = 0
[surface]
size = 64
iterations = 60
[[case]]
name = "ggx"
ndf = { type = "ggx", alpha = 0.4 }
"""


def masking_page(driver, a):
    """gonio masking's file as a page: every view drawn, the incidence selector redraws G2."""
    cfg, out = os.path.join(a.work, "masking.toml"), os.path.join(a.work, "masking.h5")
    with open(cfg, "w") as f:
        f.write(MASKING_CONFIG)
    subprocess.run([a.gonio, "masking", cfg, "-o", out, "--overwrite", "--quiet", "--no-cache",
                    "--points", "8192", "--g2-points", "2048"], check=True)
    page = os.path.join(os.path.abspath(a.work), "masking.html")
    subprocess.run([a.gonio, "report", out, "-o", page, "--overwrite", "--quiet"], check=True)
    driver.get("file://" + page)
    WebDriverWait(driver, 60).until(lambda d: drawn(d) != "")
    for view in ["m-g1", "m-furnace", "m-height", "m-g2"]:
        fp = driver.execute_script(FINGERPRINT, view)
        if not fp or fp[1] == 0:
            fail("masking page: " + view + ": nothing drawn")
    before = driver.execute_script(FINGERPRINT, "m-g2")
    state = drawn(driver)
    Select(driver.find_element("id", "m-incidence")).select_by_index(1)
    WebDriverWait(driver, 60).until(lambda d: drawn(d) != state)
    if driver.execute_script(FINGERPRINT, "m-g2") == before:
        fail("masking page: G2 did not change with the incidence")
    errors = console_errors(driver)
    if errors:
        fail("masking page: console errors: " + json.dumps(errors)[:2000])
    driver.save_screenshot(os.path.join(a.work, "masking.png"))


def main():
    p = argparse.ArgumentParser()
    p.add_argument("gonio")
    p.add_argument("work")
    p.add_argument("--screenshot")
    p.add_argument("--result")
    a = p.parse_args()
    os.makedirs(a.work, exist_ok=True)
    result, fit = (a.result, None) if a.result else make_result(os.path.abspath(a.gonio), a.work)
    page = os.path.join(os.path.abspath(a.work), "report.html")
    t0 = time.time()
    subprocess.run([a.gonio, "report", result, "-o", page, "--overwrite"] + (["--fit", fit] if fit else []),
                   check=True)
    written = time.time() - t0
    size = os.path.getsize(page)

    driver = browser()
    try:
        t0 = time.time()
        driver.get("file://" + page)
        WebDriverWait(driver, 120).until(lambda d: drawn(d) != "")
        load = time.time() - t0
        errors = console_errors(driver)
        if errors:
            fail("console errors on load: " + json.dumps(errors)[:2000])
        maps = driver.execute_script(
            "return Array.from(document.querySelectorAll('#maps > div')).map(d => d.id)")
        if "map-l1" not in maps or not any(m.startswith("map-model_") for m in maps) or \
                not any(m.startswith("map-sigma_") for m in maps):
            fail("the maps drawn are " + str(maps))
        views = ["plane", "albedo", "ledger", "ndf"] + maps
        if not a.result:  # the first case has the decomposition's models: its chart and step maps
            views.append("decomposition")
            if "map-step_1" not in maps:
                fail("no per-cell maps of the decomposition's steps: " + str(maps))
            # The random walk's orders 2 and up against simulated L2+, and the fit's residuals.
            if "map-sigma2_heitz16" not in maps or "map-fit_0" not in maps:
                fail("no L2+ sigma map of heitz16 or no fit residual map: " + str(maps))
            rows = driver.execute_script("return document.querySelectorAll('#fits tr').length")
            if rows != 2:
                fail(f"the fits table has {rows} rows, not a header and one fit")
        for view in views:
            fp = driver.execute_script(FINGERPRINT, view)
            if not fp or fp[1] == 0:
                fail(view + ": nothing drawn")

        theta = Select(driver.find_element("id", "theta"))
        if len(theta.options) < 2:
            fail("the result has one theta_i; the test needs a sweep")
        views = ["map-l1", "plane", "albedo"]
        before = {v: driver.execute_script(FINGERPRINT, v) for v in views}
        state = drawn(driver)
        t0 = time.time()
        theta.select_by_index(len(theta.options) - 1)
        WebDriverWait(driver, 60).until(lambda d: drawn(d) != state)
        redraw = time.time() - t0
        after = {v: driver.execute_script(FINGERPRINT, v) for v in views}
        for v in views:
            if before[v] == after[v]:
                fail(v + " did not change with theta_i")

        # Every case in turn: each redraws as itself; the dielectric shows its transmission.
        seen_maps = set(maps)
        cases = Select(driver.find_element("id", "case"))
        names = [o.text for o in cases.options]
        for k in (list(range(1, len(names))) + [0]) if len(names) > 1 else []:
            state = drawn(driver)
            Select(driver.find_element("id", "case")).select_by_index(k)
            WebDriverWait(driver, 60).until(lambda d: drawn(d) != state)
            if not drawn(driver).startswith(names[k] + "|"):
                fail("the case selector did not switch to " + names[k])
            seen_maps |= set(driver.execute_script(
                "return Array.from(document.querySelectorAll('#maps > div')).map(d => d.id)"))
        if not a.result and "map-t" not in seen_maps:
            fail("no transmission map for the dielectric case: " + str(sorted(seen_maps)))
        Select(driver.find_element("id", "theta")).select_by_index(1)
        errors = console_errors(driver)
        if errors:
            fail("console errors after interaction: " + json.dumps(errors)[:2000])
        if a.screenshot:
            time.sleep(0.5)
            driver.save_screenshot(a.screenshot)
        else:
            driver.save_screenshot(os.path.join(a.work, "report.png"))
        if not a.result:
            masking_page(driver, a)
    finally:
        driver.quit()
    print(f"check_report: ok: {os.path.basename(result)} -> {size / 1e6:.1f} MB page written in "
          f"{written:.2f} s, drawn in the browser in {load:.2f} s; {len(maps)} maps; a theta_i change "
          f"redrawn in {redraw:.2f} s; the case selector redraws; no console errors"
          + ("" if a.result else "; the decomposition and a gonio masking page drawn"))


if __name__ == "__main__":
    main()
