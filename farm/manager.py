"""A client of Flamenco Manager's REST API (``/api/v3``), for what Prism needs: the Manager's
version, a job type, checking and submitting jobs, and following a job and its tasks.

Standard library only (``urllib``), so it runs inside Blender without extra wheels. Every failure is a
``FlamencoError`` whose message names the Manager, what was asked and what to do about it.
"""

from __future__ import annotations

import json
import urllib.error
import urllib.parse
import urllib.request

API_PREFIX = "/api/v3"


class FlamencoError(RuntimeError):
    """The Manager could not be reached or refused a request; the message says why and what to do."""


class FlamencoManager:
    """One Flamenco Manager, by its URL (e.g. ``http://flamenco.local:8080``)."""

    def __init__(self, url: str, timeout_s: float = 10.0):
        url = url.strip().rstrip("/")
        parts = urllib.parse.urlsplit(url)
        if parts.scheme not in ("http", "https") or not parts.netloc:
            raise FlamencoError(
                f"Manager URL '{url}' is not an http(s) address: give it as shown by the Manager, "
                "e.g. http://flamenco.local:8080"
            )
        self.url = url
        self.timeout_s = timeout_s

    def version(self) -> dict:
        """The Manager's name and Flamenco version (``GET /version``)."""
        return self._request("GET", "/version")

    def job_type(self, name: str) -> dict:
        """The job type ``name`` with its settings and etag; a clear error when it is not installed."""
        try:
            return self._request("GET", f"/jobs/type/{urllib.parse.quote(name)}")
        except FlamencoError as error:
            if getattr(error, "status", None) == 404:
                raise FlamencoError(
                    f"Flamenco Manager {self.url} has no '{name}' job type: copy Prism's farm/prism_render.js "
                    "into the scripts/ folder next to the flamenco-manager executable and restart the Manager "
                    "(see docs/farm.md)."
                ) from None
            raise

    def variables(self, platform: str, audience: str = "workers") -> dict:
        """The Manager's variables as ``audience`` on ``platform`` sees them: ``{name: {"value": ...}}``."""
        return self._request("GET", f"/configuration/variables/{audience}/{urllib.parse.quote(platform)}")

    def check_job(self, submitted_job: dict) -> None:
        """Let the Manager compile ``submitted_job`` without queueing it; raises with its complaint."""
        self._request("POST", "/jobs/check", submitted_job)

    def submit_job(self, submitted_job: dict) -> dict:
        """Queue ``submitted_job``; returns the stored job (``id``, ``status``, ...)."""
        return self._request("POST", "/jobs", submitted_job)

    def job(self, job_id: str) -> dict:
        """A job's current state (``status``, ``activity``, ``steps_completed``, ...)."""
        return self._request("GET", f"/jobs/{urllib.parse.quote(job_id)}")

    def job_tasks(self, job_id: str) -> list[dict]:
        """Summaries of a job's tasks (``name``, ``status``, ``steps_completed``, ...)."""
        return self._request("GET", f"/jobs/{urllib.parse.quote(job_id)}/tasks").get("tasks") or []

    def task(self, task_id: str) -> dict:
        """One task in full: its commands and the workers that failed it."""
        return self._request("GET", f"/tasks/{urllib.parse.quote(task_id)}")

    def _request(self, method: str, path: str, body: dict | None = None) -> dict:
        address = f"{self.url}{API_PREFIX}{path}"
        data = None if body is None else json.dumps(body).encode("utf-8")
        request = urllib.request.Request(address, data=data, method=method, headers={"Accept": "application/json"})
        if data is not None:
            request.add_header("Content-Type", "application/json")
        try:
            with urllib.request.urlopen(request, timeout=self.timeout_s) as response:
                payload = response.read()
        except urllib.error.HTTPError as error:
            failure = FlamencoError(
                f"Flamenco Manager {self.url} refused {method} {path} (HTTP {error.code}): {_error_message(error)}"
            )
            failure.status = error.code
            raise failure from None
        except (urllib.error.URLError, OSError) as error:
            reason = getattr(error, "reason", error)
            raise FlamencoError(
                f"Cannot reach Flamenco Manager at {self.url} ({reason}): check that it is running and that "
                "the URL and port are the ones it prints at start-up."
            ) from None
        if not payload:
            return {}
        try:
            return json.loads(payload)
        except json.JSONDecodeError:
            raise FlamencoError(
                f"{address} did not answer with JSON: is {self.url} a Flamenco Manager (version 3 or newer)?"
            ) from None


def _error_message(error: urllib.error.HTTPError) -> str:
    """The ``message`` of Flamenco's JSON error body, else the raw text."""
    text = error.read().decode("utf-8", "replace").strip()
    try:
        return json.loads(text).get("message") or text
    except (json.JSONDecodeError, AttributeError):
        return text or error.reason
