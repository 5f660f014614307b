"""soiq's Python client against a real soiqd: the README's queries give the rows `soiq query`
prints, structures page transparently, DICOM import and upload store what the CLI's would, progress
is reported, and soiqd's errors arrive as typed exceptions with its messages."""

import csv
import re
import io
import os

import pandas
import pytest

import soiq

# The README's queries (its first session), as soiq query's options and as the client's arguments.
README_QUERIES = [
    (["--name", "hippocampus", "--min-age", "60", "--select", "voxel_volume_mm3", "--select", "sphericity",
      "--order-by", "voxel_volume_mm3"],
     dict(name="hippocampus", min_age=60, select=["voxel_volume_mm3", "sphericity"], order_by="voxel_volume_mm3")),
    (["--where", "voxel_volume_mm3>4500", "--select", "sphericity", "--order-by", "voxel_volume_mm3", "--desc",
      "--limit", "5"],
     dict(where=["voxel_volume_mm3>4500"], select=["sphericity"], order_by="voxel_volume_mm3", desc=True, limit=5)),
    (["--name", "amygdala", "--sex", "F", "--where", "mean[inside,MR]>200", "--select", "mean[shell:3,MR]",
      "--series-modality", "MR"],
     dict(name="amygdala", sex="F", where=["mean[inside,MR]>200"], select=["mean[shell:3,MR]"],
          series_modality="MR")),
    (["--name", "caudate", "--laterality", "L", "--select", "asym(voxel_volume_mm3)", "--order-by",
      "asym(voxel_volume_mm3)", "--desc", "--limit", "5"],
     dict(name="caudate", laterality="L", select=["asym(voxel_volume_mm3)"], order_by="asym(voxel_volume_mm3)",
          desc=True, limit=5)),
]


def cell(value):
    """A value as `soiq query --format csv` prints it: %.10g, several joined by ';', none empty."""
    if value is None:
        return ""
    if isinstance(value, list):
        return ";".join(cell(v) for v in value)
    if isinstance(value, float):
        return "null" if value != value else "%.10g" % value
    return str(value)


def as_csv_rows(frame):
    return [[cell(v) for v in row] for row in frame.astype(object).where(frame.notna(), None).values.tolist()]


@pytest.mark.parametrize("cli_args,kwargs", README_QUERIES)
def test_the_readmes_queries_give_the_clis_rows(demo_soiqd, cli_args, kwargs):
    printed = list(csv.reader(io.StringIO(demo_soiqd.cli("query", *cli_args, "--format", "csv"))))
    with soiq.Client(demo_soiqd.address) as c:
        frame = c.query(**kwargs)
        summary = c.last_summary
    assert isinstance(frame, pandas.DataFrame)
    assert list(frame.columns) == printed[0]
    rows = as_csv_rows(frame)
    if "order_by" not in kwargs:  # the CLI prints rows as they come: compare as sets
        rows, printed[1:] = sorted(rows), sorted(printed[1:])
    assert rows == printed[1:]
    assert len(rows) > 0
    assert summary.returned == len(rows)


def test_structures_page_transparently_and_progress_is_reported(demo_soiqd):
    with soiq.Client(demo_soiqd.address) as c:
        hippocampi = list(c.structures(name="hippocampus", page_size=7))
        assert len(hippocampi) == 40  # 20 patients, both sides: six pages
        assert len({s.id for s in hippocampi}) == 40
        assert c.info().structures == 120
        stages = []
        rows = c.query(name="amygdala", select=["voxel_volume_mm3"], as_frame=False,
                       on_progress=lambda stage, done, total: stages.append(stage))
        assert isinstance(rows, list) and len(rows) == 40
        assert "stage2" in stages or c.last_summary.cache_hits == 40


def test_import_and_upload_store_what_the_cli_would(soiqd, data):
    with soiq.Client(soiqd.address) as c:
        done = c.import_dicom([os.path.join(data, "sts/STS_002/dicom")])
        assert [p.message for p in done.problems] == []
        assert sorted(s.structure.name for s in done.structures) == ["GTV_Mass_CT", "GTV_Mass_PET"]
        frame = c.query(name="GTV*", where=["voxel_volume_mm3 > 50000"], select=["mean[inside,PT]"])
        printed = list(csv.reader(io.StringIO(soiqd.cli("query", "--name", "GTV*", "--where",
                                                        "voxel_volume_mm3 > 50000", "--select", "mean[inside,PT]",
                                                        "--format", "csv"))))
        assert sorted(as_csv_rows(frame)) == sorted(printed[1:])
        # A mesh uploaded twice (the STL `soiq download` writes of the CT's GTV): one surface stored.
        stl = os.path.join(soiqd.dir.name, "gtv.stl")
        soiqd.cli("download", str(done.structures[0].structure.id), "-o", stl)
        first = c.upload(stl, patient_id="P9", study_uid="S9", name="copy", laterality="L")
        again = c.upload(stl, patient_id="P9", study_uid="S9", name="copy again")
        assert first.structure.name == "copy" and first.structure.laterality == "L"
        assert not first.surface_already_stored and again.surface_already_stored
        assert first.structure.surface_sha256 == again.structure.surface_sha256
        assert c.delete_structure(first.structure.id) == 1
        assert [s.name for s in c.structures(patient_id="P9")] == ["copy again"]


def test_errors_are_typed_and_carry_soiqds_message(soiqd, tmp_path):
    with soiq.Client(soiqd.address) as c:
        with pytest.raises(soiq.NotFound, match="structure 424242"):
            c.structure(424242)
        with pytest.raises(soiq.InvalidArgument, match="did you mean 'sphericity'") as e:
            c.query(where=["spherity > 1"])
        assert e.value.field == "where[0]"  # soiqd's field, apart from its prose
        with pytest.raises(soiq.InvalidArgument, match="expected a comparison") as e:
            c.query(where=["sphericity"])
        assert e.value.field == ""  # the client's own refusal, before any call
        with pytest.raises(soiq.InvalidArgument, match="unknown query filter 'nmae'"):
            c.query(nmae="x")
        with pytest.raises(soiq.NotFound):
            c.import_dicom([str(tmp_path / "missing")])
    with soiq.Client("127.0.0.1:1", timeout=5) as c:
        with pytest.raises(soiq.Unavailable):
            c.info()


def test_a_token_is_sent_and_a_missing_one_is_unauthenticated(tmp_path):
    from conftest import Soiqd
    token = tmp_path / "token"
    token.write_text("python-client-token-0123456789\n")
    s = Soiqd("--token-file", str(token))
    try:
        with soiq.Client(s.address) as c:
            with pytest.raises(soiq.Unauthenticated):
                c.info()
        with soiq.Client(s.address, token_file=str(token)) as c:
            assert c.info().structures == 0
    finally:
        s.stop()


def test_the_readmes_python_example_runs_as_printed(demo_soiqd, capsys):
    readme = os.path.join(os.path.dirname(os.path.dirname(os.environ["SOIQ_TEST_DATA"])), "README.md")
    blocks = re.findall(r"```python\n(.*?)```", open(readme, encoding="utf-8").read(), re.S)
    assert len(blocks) == 1
    code = blocks[0].replace('"127.0.0.1:50051"', '"%s"' % demo_soiqd.address)
    exec(compile(code, "README.md", "exec"), {})
    out = capsys.readouterr().out
    assert "120 structures" in out
    assert "did you mean 'sphericity'" in out
    assert "voxel_volume_mm3" in out and "mean[shell:3,MR]" in out


def test_tls_with_a_verified_certificate(tmp_path):
    import subprocess
    from conftest import Soiqd
    key, cert = tmp_path / "key.pem", tmp_path / "cert.pem"
    subprocess.run(["openssl", "req", "-x509", "-newkey", "rsa:2048", "-nodes", "-keyout", str(key), "-out", str(cert),
                    "-days", "1", "-subj", "/CN=localhost", "-addext", "subjectAltName=DNS:localhost"],
                   check=True, capture_output=True)
    s = Soiqd("--tls-cert", str(cert), "--tls-key", str(key))
    try:
        port = s.address.split(":")[1]
        with soiq.Client("localhost:" + port, tls=str(cert)) as c:
            assert c.info().structures == 0
        with soiq.Client("localhost:" + port, timeout=5) as c:  # plaintext to a TLS port
            with pytest.raises(soiq.Unavailable):
                c.info()
    finally:
        s.stop()


def test_render_gives_the_picture_soiq_render_writes(demo_soiqd, tmp_path):
    c = soiq.Client(demo_soiqd.address)
    data, info = c.render(1)
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) == info.size_bytes
    assert info.media_type == "image/png" and len(info.slices) == 1
    out = tmp_path / "ct.png"
    demo_soiqd.cli("render", "1", "-o", str(out))
    assert out.read_bytes() == data  # the same drawing, byte for byte
    svg, info = c.render(1, str(tmp_path / "all.svg"), montage=True)
    assert b"<svg" in svg[:400] and len(info.slices) > 1
    with pytest.raises(soiq.errors.InvalidArgument) as refused:
        c.render(1, slice=100000)
    assert refused.value.field == "slice" and "outside 0.." in refused.value.message
    with pytest.raises(soiq.errors.NotFound):
        c.render(999999)
