"""Open a page in headless Chromium (Debian's ``chromium`` + ``chromium-driver``, installed by
``scripts/bootstrap.sh`` for the tests) through Selenium, and report what rendered.

    python tests/headless_browser.py outputs/report/report.html docs/img/report.png 2400   # screenshot, top 2400 px
"""

from __future__ import annotations

import shutil
import sys
import time
from pathlib import Path

# What the page shows once loaded: tables, images that decoded, videos with a decoded frame.
PAGE_STATE_JS = """
const vids = [...document.querySelectorAll('video')];
return {
  title: document.title,
  tables: document.querySelectorAll('table').length,
  table_rows: [...document.querySelectorAll('table')].map(t => t.querySelectorAll('tbody tr').length),
  images: [...document.images].map(i => [i.complete, i.naturalWidth, i.naturalHeight]),
  videos: vids.map(v => [v.readyState, v.videoWidth, v.videoHeight, v.error ? v.error.code : 0]),
  external: [...document.querySelectorAll('[src]')].map(e => e.getAttribute('src'))
              .filter(s => !s.startsWith('data:')),
  height: document.body.scrollHeight,
};
"""


def open_page(
    path: Path,
    screenshot: Path | None = None,
    width: int = 1280,
    timeout: float = 60.0,
    max_height: int = 6000,
) -> dict:
    """The page's state after every video has a decoded frame (or ``timeout`` passed)."""
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    driver_exe = shutil.which("chromedriver")
    if not (chromium and driver_exe):
        raise RuntimeError("headless Chromium not found: install Debian's chromium and chromium-driver")
    opts = webdriver.ChromeOptions()
    opts.binary_location = chromium
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage"):
        opts.add_argument(arg)
    opts.add_argument(f"--window-size={width},1000")
    opts.add_argument("--autoplay-policy=no-user-gesture-required")
    driver = webdriver.Chrome(service=Service(executable_path=driver_exe), options=opts)
    try:
        driver.get(Path(path).resolve().as_uri())
        deadline = time.monotonic() + timeout
        state = driver.execute_script(PAGE_STATE_JS)
        while time.monotonic() < deadline and any(v[0] < 2 and not v[3] for v in state["videos"]):
            time.sleep(0.2)
            state = driver.execute_script(PAGE_STATE_JS)
        if screenshot is not None:
            screenshot.parent.mkdir(parents=True, exist_ok=True)
            driver.set_window_size(width, min(int(state["height"]) + 40, max_height))
            time.sleep(1.0)  # let the resized page repaint the videos' first frames
            driver.save_screenshot(str(screenshot))
        return state
    finally:
        driver.quit()


if __name__ == "__main__":
    shot = Path(sys.argv[2]) if len(sys.argv) > 2 else None
    state = open_page(Path(sys.argv[1]), shot, max_height=int(sys.argv[3]) if len(sys.argv) > 3 else 6000)
    print(
        {
            k: (v if k != "videos" else f"{sum(x[0] >= 2 for x in v)}/{len(v)} decoded")
            for k, v in state.items()
        }
    )
