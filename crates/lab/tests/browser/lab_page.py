"""The lab's page in a real browser (Debian's Chromium driven by Playwright), as a coatings person
uses it: the page loads with the silver metallic; the roughness slider moved up makes the 60°
gloss fall and the 45as15 swatch change, and the picture refresh; a topography file uploaded
shows its statistics; Cornell's Cayman loaded as a target shows the ΔE00 table; the formulation
downloads as TOML; a match runs, is cancelled and fills the form; gonio selects pigments for
the Cayman target; a Morris screening draws its chart. Screenshots of each step go to OUT.

    python3 lab_page.py URL OUT TOPOGRAPHY TARGET

Prints one JSON object of what it saw (the Rust test `browser` checks it and reads the TOML).
Exits 3 when Playwright or Chromium is missing (the caller decides whether that is a skip).
"""

import json
import os
import sys
import time

try:
    from playwright.sync_api import sync_playwright
except ImportError:
    print("playwright is not installed (pip install playwright)", file=sys.stderr)
    sys.exit(3)

CHROMIUM = "/usr/bin/chromium"
if not os.path.exists(CHROMIUM):
    print(f"{CHROMIUM} is missing (apt install chromium)", file=sys.stderr)
    sys.exit(3)

url, out, topography, target = sys.argv[1:5]
os.makedirs(out, exist_ok=True)
seen = {"errors": []}
TIMEOUT = 120_000  # ms: a loaded CI machine renders slowly; the benchmarks time the lab


def reading(page, label):
    """The value (B's column) of the readings row whose first cell is `label`."""
    row = page.locator("#meters tr", has_text=label).first
    return float(row.locator("td.b").inner_text().split()[0])


def swatch(page, who, index):
    row = page.locator("#swatches .swatch-row", has=page.locator(".who", has_text=who)).first
    return row.locator(".swatch").nth(index).evaluate("e => getComputedStyle(e).backgroundColor")


def wait_idle(page, state_id, timeout=TIMEOUT):
    """Wait until the state line `state_id` no longer says it is busy."""
    page.wait_for_function(
        f"() => !document.getElementById('{state_id}').classList.contains('busy')", timeout=timeout
    )


with sync_playwright() as p:
    browser = p.chromium.launch(executable_path=CHROMIUM, args=["--no-sandbox"])
    page = browser.new_page(viewport={"width": 1280, "height": 800}, accept_downloads=True)
    page.on("pageerror", lambda e: seen["errors"].append(str(e)))
    # A refused formulation (400, step 2b) and a request cancelled by a newer one (409) are answers
    # the page expects; any other error in its console is a failure.
    page.on(
        "console",
        lambda m: m.type == "error"
        and "status of 400" not in m.text
        and "status of 409" not in m.text
        and seen["errors"].append(m.text),
    )
    page.goto(url)
    # 1. The page opens on the silver metallic, with its readings and a picture.
    page.wait_for_selector("#meters td.b", timeout=TIMEOUT)
    page.wait_for_function("() => document.getElementById('picture').naturalWidth > 0", timeout=TIMEOUT)
    wait_idle(page, "readings-state")
    page.screenshot(path=f"{out}/1-loaded.png", full_page=True)
    # The red under a rough coat: its 45as15 swatch is in the sRGB gamut (the silver's, L* 114,
    # is white however rough the top), so a change of roughness shows in its colour.
    page.select_option("#example", "red_rough")
    page.wait_for_function(
        "() => document.querySelector('input[type=number][data-path=\"top.roughness.alpha\"]')?.value === '0.15'",
        timeout=TIMEOUT,
    )
    page.wait_for_timeout(300)
    wait_idle(page, "readings-state")
    seen["gloss60_before"] = reading(page, "gloss 60°")
    seen["swatch_before"] = swatch(page, "this", 0)
    wait_idle(page, "picture-state")
    picture_before = page.get_attribute("#picture", "src")

    # 2. Move the roughness slider up (as a drag does: input events on the range).
    slider = page.locator('input[type=range][data-path="top.roughness.alpha"]')
    t0 = time.time()
    for value in (800, 850, 900):
        slider.evaluate(f"(e) => {{ e.value = {value}; e.dispatchEvent(new Event('input', {{bubbles: true}})); }}")
        page.wait_for_timeout(150)
    seen["alpha_after"] = float(page.locator('input[type=number][data-path="top.roughness.alpha"]').input_value())
    page.wait_for_function(
        f"() => {{ const r = [...document.querySelectorAll('#meters tr')].find(t => t.textContent.startsWith('gloss 60°'));"
        f" return r && Math.abs(parseFloat(r.querySelector('td.b').textContent) - {seen['gloss60_before']}) > 0.05; }}",
        timeout=TIMEOUT,
    )
    wait_idle(page, "readings-state")
    seen["readings_seconds_after_drag"] = time.time() - t0
    seen["gloss60_after"] = reading(page, "gloss 60°")
    seen["swatch_after"] = swatch(page, "this", 0)
    page.wait_for_function(
        f"() => document.getElementById('picture').src !== {json.dumps(picture_before)}", timeout=TIMEOUT
    )
    seen["picture_refreshed_seconds"] = time.time() - t0
    wait_idle(page, "picture-state")
    page.screenshot(path=f"{out}/2-rougher.png", full_page=True)

    # 2b. A value the library refuses: its message beside the field.
    page.select_option("#example", "silver_metallic")
    page.wait_for_selector('input[type=number][data-path="flakes.coverage"]', timeout=TIMEOUT)
    coverage = page.locator('input[type=number][data-path="flakes.coverage"]')
    coverage.fill("1.5")
    coverage.dispatch_event("change")
    page.wait_for_selector(".field-error", timeout=TIMEOUT)
    seen["invalid_message"] = page.inner_text(".field-error")
    seen["invalid_row"] = page.get_attribute(".row.invalid", "data-path")
    page.screenshot(path=f"{out}/2b-invalid.png", full_page=True)
    coverage.fill("0.6")
    coverage.dispatch_event("change")
    page.wait_for_function("() => !document.querySelector('.field-error')", timeout=TIMEOUT)

    # 3. Upload a topography as the top's roughness: its statistics appear.
    page.select_option('select[aria-label="surface"]', "map")
    page.set_input_files("#open-topography", topography)
    page.wait_for_selector("#topography-stats", timeout=TIMEOUT)
    seen["topography_stats"] = page.inner_text("#topography-stats")
    page.wait_for_selector("#meters td.b", timeout=TIMEOUT)
    page.screenshot(path=f"{out}/3-topography.png", full_page=True)

    # 4. A measured BRDF as the target: the ΔE00 column and the target's swatches.
    page.select_option("#example", "cayman_start")
    page.wait_for_function("() => !document.querySelector('#topography-stats')", timeout=TIMEOUT)
    page.set_input_files("#open-target", target)
    page.wait_for_selector("#swatches .who:text('target')", timeout=TIMEOUT)
    page.wait_for_function(
        "() => [...document.querySelectorAll('#colour-table th')].some(t => t.textContent === 'ΔE00')"
        " && [...document.querySelectorAll('#colour-table tr')].some(t => t.textContent.startsWith('mean ΔE00'))",
        timeout=TIMEOUT,
    )
    rows = page.locator("#colour-table tr").all_inner_texts()
    seen["de00_rows"] = rows
    page.screenshot(path=f"{out}/4-target.png", full_page=True)

    # 5. Pin A, change B, see both.
    page.click("#pin")
    page.locator('input[type=range][data-path="flakes.tilt_deg"]').evaluate(
        "(e) => { e.value = 25; e.dispatchEvent(new Event('input', {bubbles: true})); }"
    )
    page.wait_for_selector("#meters th.a", timeout=TIMEOUT)
    wait_idle(page, "readings-state")
    seen["pinned_columns"] = page.locator("#meters tr").first.inner_text()
    page.screenshot(path=f"{out}/5-pinned.png", full_page=True)

    # 6. Download the formulation as TOML.
    with page.expect_download(timeout=TIMEOUT) as download:
        page.click("#save-toml")
    path = f"{out}/formulation.toml"
    download.value.save_as(path)
    seen["toml"] = path

    # 7. The way back. Match the Cayman start to its target: a run with a large budget shows
    # its progress and is cancelled; a small one fills the form and shows its ΔE00 table.
    page.set_viewport_size({"width": 1600, "height": 1000})
    page.wait_for_function("() => !document.getElementById('match-run').disabled", timeout=TIMEOUT)
    seen["match_vary"] = page.eval_on_selector_all(
        "#match-vary input[type=checkbox]:checked", "es => es.map(e => e.dataset.name)")
    page.fill("#match-walks", "64")
    page.fill("#match-starts", "4")
    page.fill("#match-iterations", "500")
    page.click("#match-run")
    page.wait_for_function(
        "() => /best mean ΔE00 so far/.test(document.getElementById('match-line').textContent)", timeout=TIMEOUT)
    seen["match_progress_line"] = page.inner_text("#match-line")
    page.locator("#match-card").screenshot(path=f"{out}/7a-match-running.png")
    page.screenshot(path=f"{out}/7a-match-running-1600.png", full_page=True)
    page.set_viewport_size({"width": 420, "height": 900})
    page.wait_for_timeout(300)
    page.locator("#match-card").screenshot(path=f"{out}/7a-match-running-420.png")
    seen["narrow_running_overflow_px"] = page.evaluate("() => document.documentElement.scrollWidth - window.innerWidth")
    page.set_viewport_size({"width": 1600, "height": 1000})
    page.click("#match-cancel")
    page.wait_for_function(
        "() => /cancelled after/.test(document.getElementById('match-line').textContent)", timeout=TIMEOUT)
    seen["match_cancelled_line"] = page.inner_text("#match-line")
    coverage_before = page.input_value('input[type=number][data-path="flakes.coverage"]')
    page.fill("#match-starts", "1")
    page.fill("#match-iterations", "3")
    page.click("#match-run")
    page.wait_for_selector("#match-de00", timeout=TIMEOUT)
    seen["match_de00_rows"] = page.locator("#match-de00 tr").all_inner_texts()
    seen["match_values_rows"] = page.locator("#match-values tr").all_inner_texts()
    seen["match_done_line"] = page.inner_text("#match-line")
    seen["coverage_before"] = float(coverage_before)
    seen["coverage_after"] = float(page.input_value('input[type=number][data-path="flakes.coverage"]'))
    wait_idle(page, "readings-state")
    seen["form_de00_rows"] = page.locator("#colour-table tr").all_inner_texts()
    page.screenshot(path=f"{out}/7b-matched-1600.png", full_page=True)
    page.locator("#match-card").screenshot(path=f"{out}/7b-match-result.png")

    # 7c. Let gonio select up to 2 of 3 library pigments ticked, with 2 finalists, no other
    # constituent varied and a small budget: the result names the pigments chosen and lists the finalists.
    page.check("input[name=match-pigments][value=select]")
    page.wait_for_selector("#match-select:not([hidden])", timeout=TIMEOUT)
    page.fill("#match-select-max", "2")
    page.fill("#match-finalists", "2")
    for name in ("phthalo_blue_green_shade", "hansa_yellow_opaque", "bone_black"):
        page.check(f"#match-library input[value={name}]")
    page.fill("#match-iterations", "3")
    # Only the pigments' concentrations varied (a selection needs no constituent ticked): a
    # quicker match of each finalist.
    page.evaluate("""() => document.querySelectorAll('#match-vary input[type=checkbox]').forEach(b => {
        if (b.checked) b.click(); })""")
    page.locator("#match-card").screenshot(path=f"{out}/7c-select-form.png")
    page.click("#match-run")
    page.wait_for_selector("#match-chosen", timeout=TIMEOUT)
    seen["select_chosen"] = page.inner_text("#match-chosen")
    seen["select_finalists_rows"] = page.locator("#match-finalists-table tr").all_inner_texts()
    seen["select_done_line"] = page.inner_text("#match-line")
    seen["select_form_pigments"] = page.evaluate("() => (state.f.base.pigment || []).map(p => p.library || p.name)")
    page.set_viewport_size({"width": 1400, "height": 1000})
    page.wait_for_timeout(300)
    page.locator("#match-card").screenshot(path=f"{out}/7c-selected-1400.png")
    page.set_viewport_size({"width": 420, "height": 900})
    page.wait_for_timeout(300)
    page.locator("#match-card").screenshot(path=f"{out}/7c-selected-420.png")
    seen["narrow_select_overflow_px"] = page.evaluate("() => document.documentElement.scrollWidth - window.innerWidth")
    page.set_viewport_size({"width": 1600, "height": 1000})
    page.check("input[name=match-pigments][value=formulation]")

    # 8. A small Morris screening of two constituents and two readings: its chart has one bar
    # per constituent and reading, and the library's summary.
    page.evaluate("""() => document.querySelectorAll('#sens-vary input[type=checkbox]').forEach(b => {
        const on = b.dataset.name === 'tilt' || b.dataset.name === 'roughness';
        if (b.checked !== on) b.click(); })""")
    page.click("#sens-outputs summary")
    page.evaluate("""() => document.querySelectorAll('#sens-outputs input[type=checkbox]').forEach(b => {
        const on = b.value === 'gu60' || b.value === 'L@45as15';
        if (b.checked !== on) b.click(); })""")
    page.fill("#sens-samples", "2")
    page.fill("#sens-walks", "64")
    page.click("#sens-run")
    page.wait_for_function("() => /readings \\d+ of \\d+/.test(document.getElementById('sens-line').textContent)",
                           timeout=TIMEOUT)
    page.wait_for_selector("#sens-chart rect.bar", timeout=TIMEOUT)
    seen["sens_bars"] = page.eval_on_selector_all(
        "#sens-chart rect.bar", "es => es.map(e => e.dataset.output + ' ' + e.dataset.input)")
    seen["sens_summary"] = page.inner_text("#sens-summary")
    page.locator("#sensitivity-card").screenshot(path=f"{out}/8-sensitivity.png")
    page.screenshot(path=f"{out}/8-sensitivity-1600.png", full_page=True)

    # 9. A narrow window: the same page in one column.
    page.set_viewport_size({"width": 420, "height": 900})
    page.wait_for_timeout(300)
    page.screenshot(path=f"{out}/9-narrow.png", full_page=True)
    page.locator("#match-card").screenshot(path=f"{out}/9-narrow-match.png")
    page.locator("#sensitivity-card").screenshot(path=f"{out}/9-narrow-sensitivity.png")
    seen["narrow_overflow_px"] = page.evaluate("() => document.documentElement.scrollWidth - window.innerWidth")
    browser.close()

print(json.dumps(seen))
