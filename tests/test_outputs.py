"""Output paths (seatwin.outputs): never an input, never an existing file without overwrite, writable before the
work — and written through a renamed temporary file, so a failure leaves nothing half-written."""

from __future__ import annotations

import errno
import json
import os
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import seatwin.outputs as outputs
from seatwin.errors import ParameterError
from seatwin.outputs import (
    OutputExistsError,
    atomic_output,
    check_output_file,
    check_output_folder,
    check_writable,
    remove_outputs,
    write_text_atomic,
)
from seatwin.recording.manifest import check_new_run


def _run_folder(path: Path) -> Path:
    """A folder that looks like an earlier seatwin run (manifest, bag folder, scenario)."""
    (path / "recording").mkdir(parents=True)
    (path / "recording" / "recording_0.mcap").write_bytes(b"bag")
    (path / "manifest.json").write_text(json.dumps({"manifest_version": 1, "bag": "recording"}))
    (path / "scenario.yaml").write_text("name: x\n")
    return path


def test_an_output_is_never_an_input(tmp_path):
    src = tmp_path / "in.csv"
    src.write_text("x")
    (tmp_path / "link.csv").symlink_to(src)
    os.link(src, tmp_path / "hard.csv")
    for out in (src, tmp_path / "link.csv", tmp_path / "hard.csv"):
        with pytest.raises(ParameterError, match=r"is the input .*in\.csv") as err:
            check_output_file(out, "out", inputs=[src], overwrite=True)
        assert err.value.param == "out" and str(out) in str(err.value)
    assert src.read_text() == "x"


def test_an_output_never_lies_inside_an_input_run_or_bag_folder(tmp_path):
    run = _run_folder(tmp_path / "run")
    for out in (run / "manifest.json", run / "tracks.csv", run / "recording" / "x.csv"):
        with pytest.raises(ParameterError, match="inside"):
            check_output_file(out, "out", inputs=[run], overwrite=True)
    # a bag file given as input: its run folder is the input's too
    bag = run / "recording" / "recording_0.mcap"
    with pytest.raises(ParameterError, match=r"run or bag folder of the input"):
        check_output_file(run / "manifest.json", "out", inputs=[bag], overwrite=True)
    with pytest.raises(ParameterError, match="inside"):  # through a symlink to the run
        (tmp_path / "alias").symlink_to(run)
        check_output_file(tmp_path / "alias" / "t.csv", "out", inputs=[run])
    check_output_file(tmp_path / "tracks.csv", "out", inputs=[run, bag, None, "not-a-file"])  # beside it: fine


def test_an_existing_output_needs_overwrite(tmp_path):
    out = tmp_path / "t.csv"
    out.write_text("mine")
    with pytest.raises(OutputExistsError, match="exists already") as err:
        check_output_file(out, "out")
    assert err.value.param == "out" and err.value.path == out
    assert check_output_file(out, "out", overwrite=True) == out and out.read_text() == "mine"
    with pytest.raises(ParameterError, match="is a folder"):
        check_output_file(tmp_path, "out", overwrite=True)
    with pytest.raises(ParameterError, match="given twice"):
        check_output_file(tmp_path / "a.json", "json_out", outputs=[None, tmp_path / "a.json"])


def test_unwritable_outputs_are_refused_before_the_work_and_nothing_is_made(tmp_path, monkeypatch):
    long_name = tmp_path / ("a" * 300 + ".csv")
    with pytest.raises(ParameterError, match="304 bytes, longer than the 255 allowed"):
        check_output_file(long_name, "out")
    with pytest.raises(ParameterError, match="longer than"):  # a missing folder on the way, too long
        check_output_file(tmp_path / ("d" * 256) / "t.csv", "out")
    blocker = tmp_path / "file"
    blocker.write_text("x")
    with pytest.raises(ParameterError, match="is not a folder"):  # ENOTDIR
        check_output_file(blocker / "sub" / "t.csv", "out")
    before = sorted(tmp_path.iterdir())
    check_output_file(tmp_path / "new" / "deeper" / "t.csv", "out")  # missing folders: fine, made when writing
    assert sorted(tmp_path.iterdir()) == before  # the check wrote nothing

    def read_only(folder):  # what creating a file in a folder of a read-only file system raises
        raise OSError(errno.EROFS, os.strerror(errno.EROFS), str(folder))

    monkeypatch.setattr(outputs, "probe_folder", read_only)
    with pytest.raises(ParameterError, match=r"cannot write .*t\.csv: .*Read-only file system"):
        check_output_file(tmp_path / "t.csv", "out")


def test_a_folder_without_write_permission_is_refused():
    try:
        outputs.probe_folder(Path("/sys"))
    except OSError:
        pass
    else:
        pytest.skip("/sys is writable here")
    with pytest.raises(ParameterError, match=r"cannot write /sys/t\.csv: /sys: "):
        check_writable("/sys/t.csv", "out")


def test_an_output_folder_is_refused_only_for_the_entries_it_writes(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    (out / "notes.txt").write_text("mine")
    assert check_output_folder(out, "out", ["a.yaml", "a.csv"]) == []
    (out / "a.csv").write_text("old")
    with pytest.raises(OutputExistsError, match=r"a\.csv exists already"):
        check_output_folder(out, "out", ["a.yaml", "a.csv"])
    assert check_output_folder(out, "out", ["a.yaml", "a.csv"], overwrite=True) == [out / "a.csv"]
    with pytest.raises(ParameterError, match="would replace the input"):
        check_output_folder(out, "out", ["a.yaml", "a.csv"], inputs=[out / "a.csv"], overwrite=True)
    with pytest.raises(ParameterError, match="exists and is not a folder"):
        check_output_folder(out / "notes.txt", "out", ["a.csv"])


def test_a_run_folder_is_new_or_empty_or_replaced_only_where_seatwin_wrote(tmp_path):
    assert check_new_run(tmp_path / "new", "out") == []
    (tmp_path / "empty").mkdir()
    assert check_new_run(tmp_path / "empty", "out") == []
    users = tmp_path / "users"
    users.mkdir()
    (users / "scenario.csv").write_text("a user's scenario")
    with pytest.raises(OutputExistsError, match="exists and is not empty"):
        check_new_run(users, "out")
    with pytest.raises(ParameterError, match=r"scenario\.csv was not written by seatwin"):
        check_new_run(users, "out", overwrite=True)
    assert (users / "scenario.csv").read_text() == "a user's scenario"

    run = _run_folder(tmp_path / "run")
    (run / "notes.txt").write_text("mine")
    with pytest.raises(OutputExistsError):
        check_new_run(run, "out")
    stale = check_new_run(run, "out", overwrite=True)
    assert sorted(p.name for p in stale) == ["manifest.json", "recording", "scenario.yaml"]
    with pytest.raises(ParameterError, match=r"is .*run, the run or bag folder of the input .*scenario\.yaml"):
        check_new_run(run, "out", inputs=[run / "scenario.yaml"], overwrite=True)
    remove_outputs(stale)
    assert sorted(p.name for p in run.iterdir()) == ["notes.txt"]


def test_atomic_output_replaces_at_the_end_or_leaves_nothing(tmp_path):
    out = tmp_path / "sub" / "t.csv"
    with pytest.raises(RuntimeError), atomic_output(out) as tmp:
        assert tmp.suffix == ".csv" and tmp.parent == out.parent
        tmp.write_text("half")
        raise RuntimeError("killed")
    assert list(out.parent.iterdir()) == []
    out.write_text("old")
    with pytest.raises(RuntimeError), atomic_output(out) as tmp:
        tmp.write_text("half")
        raise RuntimeError("killed")
    assert out.read_text() == "old" and list(out.parent.iterdir()) == [out]
    write_text_atomic(out, "new")
    assert out.read_text() == "new" and list(out.parent.iterdir()) == [out]
    assert oct(out.stat().st_mode & 0o777) == oct(0o666 & ~_umask())


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


_NAMES = st.text(alphabet="abcXY_.-", min_size=1, max_size=12).filter(lambda n: n not in (".", ".."))


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(inside=st.lists(_NAMES, min_size=1, max_size=4), beside=st.lists(_NAMES, min_size=1, max_size=4))
def test_any_path_inside_an_input_folder_is_refused_and_any_beside_it_is_not(tmp_path, inside, beside):
    """Property: through a symlink or not, a path under an input folder is refused; one in a sibling folder is not."""
    run = tmp_path / "run"
    if not run.exists():
        _run_folder(run)
        (tmp_path / "alias").symlink_to(run)
    for base in (run, tmp_path / "alias"):
        with pytest.raises(ParameterError, match="inside the input"):
            outputs.refuse_inputs(base.joinpath(*inside), "out", [run])
    outputs.refuse_inputs(tmp_path.joinpath("elsewhere", *beside), "out", [run, run / "scenario.yaml"])
