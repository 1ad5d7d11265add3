"""farm/manager.py without a Manager: addresses it refuses and a Manager that is not there.
(Talking to a real Manager is in test_flamenco_farm.py.)"""

from __future__ import annotations

import pytest

from farm.manager import FlamencoError, FlamencoManager


@pytest.mark.parametrize("url", ["localhost:8080", "ftp://flamenco.local", "http://", ""])
def test_addresses_that_are_not_http_urls_are_refused(url):
    with pytest.raises(FlamencoError, match="is not an http\\(s\\) address: give it as shown by the Manager"):
        FlamencoManager(url)


def test_trailing_slash_and_spaces_are_dropped():
    assert FlamencoManager("  http://flamenco.local:8080/ ").url == "http://flamenco.local:8080"


def test_unreachable_manager_names_the_url_and_what_to_check(unreachable_url):
    manager = FlamencoManager(unreachable_url, timeout_s=2.0)
    with pytest.raises(FlamencoError, match=f"Cannot reach Flamenco Manager at {unreachable_url} .*check that it is running"):
        manager.version()
