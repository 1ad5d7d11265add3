"""farm/submission.py: the SubmittedJob document, frame ranges, chunk sizes, and the check for an
outdated job type on the Manager."""

from __future__ import annotations

import pytest

from farm import JOB_TYPE_NAME
from farm.manager import FlamencoError
from farm.submission import PrismFarmJob, frame_range_text, samples_per_chunk, submit, submitter_platform


def _job(**changes):
    values = dict(name="shot 010", blendfile="/render/shot.blend", frames="1..24", samples=64, chunks=4, seed=3,
                  render_output_path="/render/shot/prism_####.exr")
    values.update(changes)
    return PrismFarmJob(**values)


def test_submitted_job_is_flamencos_document():
    document = _job(priority=70).submitted_job(type_etag="abc", platform="linux")
    assert document == {
        "name": "shot 010",
        "type": JOB_TYPE_NAME,
        "priority": 70,
        "submitter_platform": "linux",
        "type_etag": "abc",
        "settings": {
            "blendfile": "/render/shot.blend",
            "frames": "1..24",
            "samples": 64,
            "chunks": 4,
            "samples_per_pass": 1,
            "seed": 3,
            "render_output_path": "/render/shot/prism_####.exr",
            "render_script": "{prism}/render.py",
        },
    }
    assert "type_etag" not in _job().submitted_job()
    assert _job().submitted_job()["submitter_platform"] == submitter_platform() == "linux"


def test_frame_ranges_in_flamenco_notation():
    assert frame_range_text(1, 250) == "1..250"
    assert frame_range_text(7, 7) == "7..7"
    assert frame_range_text(1, 10, 3) == "1,4,7,10"
    with pytest.raises(ValueError, match="no negative frames \\(the range starts at -2\\): set the scene's Frame Start"):
        frame_range_text(-2, 1)
    with pytest.raises(ValueError, match="ends \\(3\\) before it starts \\(5\\)"):
        frame_range_text(5, 3)


def test_samples_split_into_equal_chunks_or_the_fix_is_named():
    assert samples_per_chunk(64, 4) == 16
    assert samples_per_chunk(5, 1) == 5
    with pytest.raises(ValueError, match="64 samples do not split into 3 equal chunks: set Samples to 63 or 66"):
        samples_per_chunk(64, 3)
    with pytest.raises(ValueError, match="set Samples to 4,"):
        samples_per_chunk(2, 4)
    with pytest.raises(ValueError, match="must both be at least 1"):
        samples_per_chunk(64, 0)


class _ManagerWithJobType:
    """The part of FlamencoManager ``submit`` uses, holding a given job type."""

    url = "http://flamenco.local:8080"

    def __init__(self, keys, variables=("prism",)):
        self.job_type_settings = [{"key": key, "type": "string"} for key in keys]
        self.worker_variables = {name: {"value": "/opt/prism", "is_twoway": False} for name in variables}
        self.submitted = []

    def variables(self, platform):
        return self.worker_variables if platform == "windows" else {}

    def job_type(self, name):
        assert name == JOB_TYPE_NAME
        return {"name": name, "etag": "e1", "settings": self.job_type_settings}

    def submit_job(self, document):
        self.submitted.append(document)
        return {"id": "job-1", "status": "queued"}


def test_submit_sends_the_job_type_etag():
    manager = _ManagerWithJobType(_job().settings())
    assert submit(manager, _job()) == {"id": "job-1", "status": "queued"}
    assert manager.submitted[0]["type_etag"] == "e1"


def test_submit_names_an_outdated_job_type_on_the_manager():
    manager = _ManagerWithJobType(["blendfile", "frames", "samples", "chunks", "seed", "render_output_path",
                                   "render_script"])  # the job type of Prism before samples_per_pass
    with pytest.raises(FlamencoError, match="older than this Prism \\(no samples_per_pass setting\\): copy"):
        submit(manager, _job())
    assert manager.submitted == []


def test_submit_names_a_variable_the_manager_lacks():
    manager = _ManagerWithJobType(_job().settings(), variables=("blender",))
    with pytest.raises(FlamencoError, match="has no 'prism' variable, which Render Script '{prism}/render.py' uses"):
        submit(manager, _job())
    assert manager.submitted == []
    assert submit(manager, _job(render_script="/opt/prism/render.py"))["id"] == "job-1"
