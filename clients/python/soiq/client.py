"""soiq's Python client: a small layer over the gRPC stubs generated from proto/ (soiq.v1).

    import soiq
    with soiq.Client("127.0.0.1:50051") as c:
        c.import_dicom(["STS_002/dicom"])
        frame = c.query(name="GTV*", where=["voxel_volume_mm3 > 1000"], select=["mean[inside,PT]"])

Every failure is a soiq.SoiqError subclass (soiq.errors) carrying soiqd's message. Calls have a
deadline (`timeout` seconds, per call; queries and imports take `timeout` for their whole stream).
"""

import os

import grpc

from soiq import errors
from soiq.query_options import OPTIONS, python_name, query_columns, query_request
from soiq.v1 import soiq_pb2, soiq_pb2_grpc

_CHUNK = 1 << 20
_MAX_MESSAGE = 16 << 20


def _chunks(path):
    """A file's bytes in pieces of _CHUNK, as the upload streams send them."""
    with open(path, "rb") as f:
        while True:
            chunk = f.read(_CHUNK)
            if not chunk:
                return
            yield chunk


def _call(fn, *args, **kwargs):
    try:
        return fn(*args, **kwargs)
    except grpc.RpcError as e:
        raise errors.from_rpc_error(e) from None


class Client:
    """A connection to soiqd.

    address: "host:port". token / token_file: the bearer token soiqd was started with
    (--token-file). tls: True to use TLS with the system's roots, or the path of a CA certificate
    (PEM) to trust; False for plaintext. timeout: seconds per call.
    """

    def __init__(self, address="127.0.0.1:50051", token=None, token_file=None, tls=False, timeout=600.0):
        if token_file is not None:
            with open(token_file) as f:
                token = f.read().strip()
        self._metadata = (("authorization", "Bearer " + token),) if token else ()
        options = [("grpc.max_receive_message_length", _MAX_MESSAGE),
                   ("grpc.max_send_message_length", _MAX_MESSAGE)]
        if tls:
            roots = None
            if isinstance(tls, (str, os.PathLike)):
                with open(tls, "rb") as f:
                    roots = f.read()
            self._channel = grpc.secure_channel(address, grpc.ssl_channel_credentials(roots), options)
        else:
            self._channel = grpc.insecure_channel(address, options)
        self._stub = soiq_pb2_grpc.SoiqStub(self._channel)
        self.timeout = timeout

    def close(self):
        self._channel.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def _unary(self, method, request):
        return _call(method, request, timeout=self.timeout, metadata=self._metadata)

    # --- records -------------------------------------------------------------------------------

    def info(self):
        """soiqd's version, limits, counts and feature catalogue (soiq_pb2.ServerInfo)."""
        return self._unary(self._stub.GetServerInfo, soiq_pb2.GetServerInfoRequest())

    def structures(self, patient_id="", study_uid="", name="", laterality="", page_size=500):
        """Every structure the filter keeps (soiq_pb2.Structure), fetched page by page as iterated.
        patient_id: exact, or a glob with * ? [; name: a case-insensitive glob."""
        token = ""
        while True:
            page = self._unary(self._stub.ListStructures, soiq_pb2.ListStructuresRequest(
                patient_id=patient_id, study_uid=study_uid, name_glob=name, laterality=laterality,
                page_size=page_size, page_token=token))
            yield from page.structures
            token = page.next_page_token
            if not token:
                return

    def structure(self, structure_id):
        return self._unary(self._stub.GetStructure, soiq_pb2.GetStructureRequest(id=structure_id))

    def delete_structure(self, structure_id):
        return self._unary(self._stub.DeleteStructure, soiq_pb2.DeleteStructureRequest(id=structure_id)).structures_deleted

    # --- uploads -------------------------------------------------------------------------------

    def upload(self, path, patient_id, study_uid, name, laterality="", robust=False, sex="", birth_date="",
               study_date="", modality="", coordinates="LPS"):
        """Uploads a surface mesh file (stl, obj, ply, vtk, vtp: by its extension) as a structure;
        returns soiq_pb2.UploadSurfaceResponse (the structure, whether its surface was stored
        already, its defects)."""
        fmt = os.path.splitext(str(path))[1].lstrip(".").lower()
        header = soiq_pb2.UploadSurfaceHeader(
            patient=soiq_pb2.Patient(patient_id=patient_id, sex=sex, birth_date=birth_date),
            study=soiq_pb2.Study(study_uid=study_uid, study_date=study_date, modality=modality),
            structure_name=name, laterality=laterality, format=fmt, robust=robust,
            coordinates=soiq_pb2.RAS if coordinates == "RAS" else soiq_pb2.LPS)

        def requests():
            yield soiq_pb2.UploadSurfaceRequest(header=header)
            for chunk in _chunks(path):
                yield soiq_pb2.UploadSurfaceRequest(chunk=chunk)

        return _call(self._stub.UploadSurface, requests(), timeout=self.timeout, metadata=self._metadata)

    def import_dicom(self, paths):
        """Sends DICOM files and folders (walked; DICOMDIRs work) to soiqd, which stores CT, MR and
        PET series as images and RT Structure Set and SEG structures, as `soiq import` does;
        returns soiq_pb2.ImportDicomResponse (what was stored, the problems)."""
        files = []
        for p in ([paths] if isinstance(paths, (str, os.PathLike)) else paths):
            p = str(p)
            if os.path.isdir(p):
                base = os.path.dirname(os.path.abspath(p))
                for root, _, names in sorted(os.walk(p)):
                    for n in sorted(names):
                        full = os.path.join(root, n)
                        files.append((full, os.path.relpath(full, base).replace(os.sep, "/")))
            elif os.path.isfile(p):
                files.append((p, os.path.basename(p)))
            else:
                raise errors.NotFound("'%s': no such file or folder" % p)

        def requests():
            for full, relative in files:
                yield soiq_pb2.ImportDicomRequest(
                    file=soiq_pb2.ImportFileHeader(path=relative, size_bytes=os.path.getsize(full)))
                for chunk in _chunks(full):
                    yield soiq_pb2.ImportDicomRequest(chunk=chunk)

        return _call(self._stub.ImportDicom, requests(), timeout=self.timeout, metadata=self._metadata)

    # --- pictures ------------------------------------------------------------------------------

    _FORMATS = {".png": soiq_pb2.PNG, ".svg": soiq_pb2.SVG, ".jpg": soiq_pb2.JPEG, ".jpeg": soiq_pb2.JPEG}

    def render(self, structure_id, path=None, image="", plane="axial", slice=None, through="largest",
               window=None, montage=False, width=0, patient_caption=False, format="png", jpeg_quality=0):
        """A picture of a structure over a slice of its image, as `soiq render` draws it: its bytes,
        also written to `path` when given (whose extension then chooses the format). window:
        (centre, width) or None for the image's own. Returns (bytes, soiq_pb2.RenderInfo);
        IPython.display.Image(data=bytes) shows it in a notebook."""
        if path is not None:
            format = os.path.splitext(path)[1].lower()
        else:
            format = "." + format.lower().lstrip(".")
        if format not in self._FORMATS:
            raise errors.InvalidArgument("a picture is .png, .svg or .jpg, not '%s'" % format)
        if plane not in ("axial", "coronal", "sagittal"):
            raise errors.InvalidArgument("plane must be axial, coronal or sagittal, not '%s'" % plane)
        if through not in ("largest", "centroid"):
            raise errors.InvalidArgument("through must be largest or centroid, not '%s'" % through)
        request = soiq_pb2.RenderRequest(
            structure_id=structure_id, image=image, plane=soiq_pb2.Plane.Value(plane.upper()),
            through=soiq_pb2.SliceChoice.Value(through.upper()), montage=montage, width=width,
            format=self._FORMATS[format], jpeg_quality=jpeg_quality, patient_caption=patient_caption)
        if slice is not None:
            request.slice = slice
        if window is not None:
            request.window_center, request.window_width = window
        info, chunks = None, []
        try:
            for part in self._stub.Render(request, timeout=self.timeout, metadata=self._metadata):
                if part.HasField("info"):
                    info = part.info
                else:
                    chunks.append(part.chunk)
        except grpc.RpcError as e:
            raise errors.from_rpc_error(e) from None
        data = b"".join(chunks)
        if info is None or len(data) != info.size_bytes:
            raise errors.DataLoss("soiqd sent a picture of %d bytes, announced %s" %
                                  (len(data), info.size_bytes if info else "nothing"))
        if path is not None:
            with open(path, "wb") as f:
                f.write(data)
        return data, info

    # --- the two-stage query -------------------------------------------------------------------

    def query_rows(self, where=(), select=(), order_by=None, desc=False, limit=0, spacing=None, margin=None,
                   series_modality="", interpolation=None, on_progress=None, **stage1):
        """Runs the query and yields each row as a dict as soiqd streams it: id, patient_id,
        study_uid, name, laterality, then one key per feature (where's, select's, order_by's, as
        `soiq query` heads its columns; a list for array features, None when a row has no value).
        The last thing set is `self.last_summary` (soiq_pb2.QuerySummary).

        stage1: patient, sex, min_age, max_age, birth_date_from, birth_date_to, study_date_from,
        study_date_to, modality, description, name, laterality (as soiq query's options).
        on_progress(stage, done, total) is called as stage 1 and stage 2 advance."""
        request = self._query_request(where, select, order_by, desc, limit, spacing, margin, series_modality,
                                      interpolation, stage1)
        columns = query_columns(request)
        self.last_summary = None
        events = _call(self._stub.Query, request, timeout=self.timeout, metadata=self._metadata)
        try:
            for event in events:
                kind = event.WhichOneof("event")
                if kind == "progress" and on_progress is not None:
                    on_progress(event.progress.stage, event.progress.done, event.progress.total)
                elif kind == "row":
                    yield _row_dict(event.row, columns)
                elif kind == "summary":
                    self.last_summary = event.summary
        except grpc.RpcError as e:
            raise errors.from_rpc_error(e) from None

    def query(self, *args, as_frame=True, **kwargs):
        """query_rows, collected: a pandas DataFrame (one row per structure, ordered as soiqd sent
        them) when pandas is installed and as_frame, else a list of dicts."""
        rows = list(self.query_rows(*args, **kwargs))
        if not as_frame:
            return rows
        try:
            import pandas
        except ImportError:
            return rows
        return pandas.DataFrame(rows, columns=list(rows[0].keys()) if rows else None)

    @staticmethod
    def _query_request(where, select, order_by, desc, limit, spacing, margin, series_modality, interpolation,
                       stage1):
        """The options as the one query table's (name, value) pairs (soiq.query_options)."""
        options = []
        stage1_names = [name for name, _, _ in OPTIONS[:12]]
        for key, value in stage1.items():
            name = key.replace("_", "-")
            if name not in stage1_names:
                raise errors.InvalidArgument("unknown query filter '%s' (known: %s)" % (
                    key, ", ".join(python_name(n) for n in stage1_names)))
            if value is not None:
                options.append((name, value))
        options += [("where", w) for w in ([where] if isinstance(where, str) else where)]
        options += [("select", s) for s in ([select] if isinstance(select, str) else select)]
        if order_by is not None:
            options.append(("order-by", order_by))
        if desc:
            options.append(("desc", True))
        if limit:
            options.append(("limit", limit))
        if spacing is not None:
            options.append(("spacing", spacing))
        if margin is not None:
            options.append(("margin", margin))
        if series_modality:
            options.append(("series-modality", series_modality))
        if interpolation is not None:
            options.append(("interpolation", interpolation))
        return query_request(options)


def _row_dict(row, columns):
    """A row as a dict keyed by the answer's columns (query_columns: the header and, per feature
    column, where its value is in the row)."""
    header, value_at = columns
    s = row.structure
    out = dict(zip(header, (s.id, s.patient_id, s.study_uid, s.name, s.laterality)))
    for column, i in zip(header[len(out):], value_at):
        values = list(row.values[i].value) if i < len(row.values) else []
        out[column] = None if not values else values[0] if len(values) == 1 else values
    return out
