#!/usr/bin/python3
"""The Python client (examples/python) against a real acommsd: every error
status the API documents, reached from Python, and the calls that succeed.

    python_client_test.py --acommsd build/daemon/acommsd --generated DIR [unittest args]

The stubs are generated into DIR first (examples/python/generate.sh, plus the
test's own DCCL types). The daemon runs the sim driver with mac "none", so
nothing is ever sent: queued messages stay queued and a subscription stays
silent (the end-to-end subscribe runs two daemons, in another test).

Exits 77 (ctest: skipped) when python3-grpcio / python3-protobuf are not
installed for this interpreter.
"""

import argparse
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
import unittest

SKIP = 77
SOURCE_DIR = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
EXAMPLES_DIR = os.path.join(SOURCE_DIR, "examples", "python")
TEST_PROTO_DIR = os.path.join(SOURCE_DIR, "tests", "integration", "proto")
API_PROTO_DIR = os.path.join(SOURCE_DIR, "api", "proto")

try:
    import grpc  # noqa: F401
    import google.protobuf  # noqa: F401
except ImportError as e:
    print(f"SKIP: {e}: python3-grpcio and python3-protobuf are not installed for {sys.executable} "
          "(apt-get install python3-grpcio python3-protobuf, or packaging/install-deps.sh --test)",
          file=sys.stderr)
    sys.exit(SKIP)

ACOMMSD = None  # set from the command line
GENERATED = None


def free_tcp_port():
    import socket
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def make_certificates(out_dir):
    """A CA, a daemon certificate for 127.0.0.1 and a client certificate, made
    with the openssl command."""
    def openssl(*args):
        subprocess.run(["openssl", *args], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)

    def path(name):
        return os.path.join(out_dir, name)

    with open(path("server.ext"), "w") as f:
        f.write("subjectAltName=IP:127.0.0.1\n")
    for name in ("ca", "server", "client"):
        openssl("genpkey", "-algorithm", "EC", "-pkeyopt", "ec_paramgen_curve:prime256v1", "-out", path(name + ".key"))
    openssl("req", "-x509", "-new", "-key", path("ca.key"), "-out", path("ca.pem"), "-days", "2", "-subj", "/CN=py CA")
    for name, ext in (("server", ["-extfile", path("server.ext")]), ("client", [])):
        openssl("req", "-new", "-key", path(name + ".key"), "-out", path(name + ".csr"), "-subj", "/CN=" + name)
        openssl("x509", "-req", "-in", path(name + ".csr"), "-CA", path("ca.pem"), "-CAkey", path("ca.key"),
                "-set_serial", "7" if name == "server" else "8", "-days", "2", "-out", path(name + ".pem"), *ext)


def generate_stubs(out_dir):
    """The API stubs, and the test's DCCL types as Python classes."""
    subprocess.run(["bash", os.path.join(EXAMPLES_DIR, "generate.sh"), out_dir], check=True,
                   stdout=subprocess.DEVNULL)
    subprocess.run([os.environ.get("PROTOC", "/usr/bin/protoc"), "-I", API_PROTO_DIR, "-I", TEST_PROTO_DIR,
                    f"--python_out={out_dir}", "dccl/option_extensions.proto", "python_test.proto"],
                   check=True)


class PythonClientTest(unittest.TestCase):
    """One daemon for the whole class; each test uses its own messages."""

    @classmethod
    def setUpClass(cls):
        global AcommsClient, AcommsError, python_test_pb2
        sys.path.insert(0, EXAMPLES_DIR)
        os.environ["ACOMMS_PYTHON_GENERATED"] = GENERATED
        from acomms_client import AcommsClient, AcommsError  # noqa: E402
        sys.path.insert(0, GENERATED)
        import python_test_pb2  # noqa: E402

        # Short: unix socket paths are limited to 107 bytes.
        cls.dir = tempfile.mkdtemp(prefix="acomms-py-", dir="/tmp")
        cls.socket = os.path.join(cls.dir, "api.sock")
        # Also mutual TLS on loopback TCP, for the TLS example.
        make_certificates(cls.dir)
        cls.tcp = f"127.0.0.1:{free_tcp_port()}"
        config = os.path.join(cls.dir, "acommsd.conf")
        with open(config, "w") as f:
            f.write(f"""data_dir: "{cls.dir}/data"
log_level: INFO
grpc {{
  unix_socket: "{cls.socket}"
  tcp_listen: "{cls.tcp}"
  tls {{
    cert_file: "{cls.dir}/server.pem"
    key_file: "{cls.dir}/server.key"
    client_ca_file: "{cls.dir}/ca.pem"
  }}
}}
driver {{ name: "sim" modem_id: 1 }}
mac {{ name: "none" }}
dccl {{
  proto_files: "{os.path.join(TEST_PROTO_DIR, 'python_test.proto')}"
  # Out-of-range values are refused (INVALID_ARGUMENT), not zeroed.
  strict: true
}}
queue {{
  type {{ type: "pytest.Beacon" policy {{ max_queue: 1 on_full: REFUSE_NEW }} }}
}}
""")
        cls.log_path = os.path.join(cls.dir, "acommsd.log")
        cls.log = open(cls.log_path, "w")
        cls.daemon = subprocess.Popen([ACOMMSD, "--config", config], stdin=subprocess.DEVNULL,
                                      stdout=cls.log, stderr=subprocess.STDOUT)
        cls.client = None
        deadline = time.monotonic() + 20
        last_error = "no socket yet"
        while time.monotonic() < deadline:
            if cls.daemon.poll() is not None:
                break
            if os.path.exists(cls.socket):
                try:
                    client = AcommsClient(cls.socket, timeout=2)
                    client.status()
                    client.timeout = 10
                    cls.client = client
                    break
                except AcommsError as e:
                    last_error = str(e)
                    client.close()
            time.sleep(0.05)
        if cls.client is None:
            cls._stop_daemon()
            log = cls._log_text()
            shutil.rmtree(cls.dir, ignore_errors=True)
            raise RuntimeError(f"acommsd did not start serving ({last_error}):\n{log}")

    @classmethod
    def _log_text(cls):
        if not cls.log.closed:
            cls.log.flush()
        with open(cls.log_path) as f:
            return f.read()

    @classmethod
    def _stop_daemon(cls):
        if cls.daemon.poll() is None:
            cls.daemon.send_signal(signal.SIGTERM)
            try:
                cls.daemon.wait(15)
            except subprocess.TimeoutExpired:
                cls.daemon.kill()
                cls.daemon.wait()
        cls.log.close()
        return cls.daemon.returncode

    @classmethod
    def tearDownClass(cls):
        cls.client.close()
        code = cls._stop_daemon()
        log = cls._log_text()
        shutil.rmtree(cls.dir, ignore_errors=True)
        if code != 0:
            raise AssertionError(f"acommsd exited with {code} after SIGTERM:\n{log}")

    def test_mutual_tls_client_with_a_certificate_is_served(self):
        with AcommsClient(self.tcp, timeout=5, tcp=True, ca_file=f"{self.dir}/ca.pem",
                          cert_file=f"{self.dir}/client.pem", key_file=f"{self.dir}/client.key") as tls:
            self.assertEqual(tls.status().version, self.client.status().version)

    def test_mutual_tls_client_without_a_certificate_is_refused(self):
        with AcommsClient(self.tcp, timeout=5, tcp=True, ca_file=f"{self.dir}/ca.pem") as tls:
            self.assertFails(grpc.StatusCode.UNAVAILABLE, tls.status)

    def assertFails(self, code, call, *args, contains=(), **kwargs):
        """`call` raises AcommsError with `code`, its message holding each of
        `contains`; returns the error."""
        with self.assertRaises(AcommsError) as caught:
            call(*args, **kwargs)
        error = caught.exception
        self.assertEqual(error.code, code, f"expected {code.name}, got: {error}")
        for text in contains:
            self.assertIn(text, error.details, f"{error}")
        return error

    def queued_ids(self, type=""):
        return [m.message_id for m in self.client.list_queued(type)]

    # ---------------------------------------------------------------- success

    def test_status_reports_the_setup(self):
        status = self.client.status()
        self.assertEqual(status.driver, "sim")
        self.assertEqual(status.mac, "none")
        self.assertEqual(status.modem_id, 1)
        self.assertGreaterEqual(status.dccl_types, 2)

    def test_submitted_dict_is_listed_as_queued(self):
        message_id = self.client.submit("pytest.Report", {"depth": 12.5, "mode": "SURVEY", "battery": 80})
        self.assertGreater(message_id, 0)
        listed = {m.message_id: m for m in self.client.list_queued("pytest.Report")}
        self.assertIn(message_id, listed)
        queued = listed[message_id]
        self.assertEqual(queued.type, "pytest.Report")
        self.assertFalse(queued.in_flight)
        self.assertGreater(queued.encoded_bytes, 0)
        self.assertAlmostEqual(json.loads(queued.json)["depth"], 12.5)
        self.assertEqual(json.loads(queued.json)["mode"], "SURVEY")

    def test_submit_protobuf_message_bytes_and_ttl(self):
        report = python_test_pb2.Report(depth=3, mode=python_test_pb2.Report.TRANSIT)
        by_message = self.client.submit("pytest.Report", report, ttl=60)
        by_bytes = self.client.submit("pytest.Report", report.SerializeToString())
        self.assertNotEqual(by_message, by_bytes)
        listed = {m.message_id: m for m in self.client.list_queued("pytest.Report")}
        self.assertIn(by_message, listed)
        self.assertIn(by_bytes, listed)
        self.assertAlmostEqual(listed[by_message].ttl_s, 60)
        self.assertAlmostEqual(listed[by_message].expires_at - listed[by_message].submitted_at, 60, places=3)

    def test_cancel_removes_then_not_found(self):
        message_id = self.client.submit("pytest.Report", {"depth": 1})
        self.client.cancel(message_id, reason="python test")
        self.assertNotIn(message_id, self.queued_ids("pytest.Report"))
        self.assertFails(grpc.StatusCode.NOT_FOUND, self.client.cancel, message_id)

    def test_flush_removes_every_message_of_a_type(self):
        ids = [self.client.submit("pytest.Report", {"depth": d}) for d in (4, 5)]
        self.assertGreaterEqual(self.client.flush("pytest.Report"), len(ids))
        self.assertEqual(self.queued_ids("pytest.Report"), [])

    def test_load_inline_definitions_adds_a_queue(self):
        text = ('syntax = "proto2";\nimport "dccl/option_extensions.proto";\npackage pyinline;\n'
                'message Ping {\n  option (dccl.msg) = { codec_version: 4 id: 63 max_bytes: 4 };\n'
                '  required uint32 n = 1 [(dccl.field) = { min: 0 max: 15 }];\n}\n')
        types = self.client.load_definitions(inline={"py_inline.proto": text})
        self.assertIn("pyinline.Ping", [t.name for t in types])
        message_id = self.client.submit("pyinline.Ping", {"n": 7})
        self.assertIn(message_id, self.queued_ids("pyinline.Ping"))

    def test_subscribe_opens_and_is_cancellable(self):
        subscription = self.client.subscribe(["pytest.Report"], src=2)
        received, errors = [], []

        def read():
            try:
                for message in subscription:
                    received.append(message)
            except Exception as e:  # noqa: BLE001 - reported below
                errors.append(e)

        reader = threading.Thread(target=read, daemon=True)
        reader.start()
        reader.join(1.0)
        self.assertEqual(errors, [], "the stream ended with an error")
        self.assertTrue(reader.is_alive() and subscription.is_active(), "the stream did not stay open")
        subscription.cancel()
        reader.join(5)
        self.assertFalse(reader.is_alive(), "cancel() did not end the iteration")
        self.assertEqual(errors, [], "cancel() raised instead of ending quietly")
        self.assertEqual(received, [], "mac none sends nothing, so nothing arrives")

    # ---------------------------------------------------------------- NOT_FOUND

    def test_submit_unknown_type_is_not_found(self):
        error = self.assertFails(grpc.StatusCode.NOT_FOUND, self.client.submit, "pytest.Nope", {"a": 1},
                                 contains=["pytest.Nope"])
        self.assertTrue(str(error).startswith("Submit: NOT_FOUND: "), str(error))

    def test_cancel_unknown_id_is_not_found(self):
        self.assertFails(grpc.StatusCode.NOT_FOUND, self.client.cancel, 987654321)

    def test_flush_unknown_type_is_not_found(self):
        self.assertFails(grpc.StatusCode.NOT_FOUND, self.client.flush, "pytest.Nope", contains=["pytest.Nope"])

    def test_load_missing_path_is_not_found(self):
        missing = os.path.join(self.dir, "missing.proto")
        self.assertFails(grpc.StatusCode.NOT_FOUND, self.client.load_definitions, [missing],
                         contains=["missing.proto"])

    # ---------------------------------------------------------------- INVALID_ARGUMENT

    def test_out_of_range_names_the_field_and_bound(self):
        before = self.queued_ids("pytest.Report")
        self.assertFails(grpc.StatusCode.INVALID_ARGUMENT, self.client.submit, "pytest.Report",
                         {"depth": 5000}, contains=["depth", "1000"])
        self.assertFails(grpc.StatusCode.INVALID_ARGUMENT, self.client.submit, "pytest.Report",
                         {"depth": 10, "battery": 101}, contains=["battery", "100"])
        self.assertEqual(self.queued_ids("pytest.Report"), before, "nothing was changed")

    def test_malformed_json_is_invalid_argument(self):
        self.assertFails(grpc.StatusCode.INVALID_ARGUMENT, self.client.submit, "pytest.Report", '{"depth": ')
        self.assertFails(grpc.StatusCode.INVALID_ARGUMENT, self.client.submit, "pytest.Report",
                         {"depth": 1, "mode": "DIVE"})

    def test_missing_required_field_is_invalid_argument(self):
        self.assertFails(grpc.StatusCode.INVALID_ARGUMENT, self.client.submit, "pytest.Report", {},
                         contains=["depth"])

    def test_bad_inline_proto_is_invalid_argument(self):
        syntax_error = 'syntax = "proto2";\npackage pybad;\nmessage Broken { required int32 = 1; }\n'
        self.assertFails(grpc.StatusCode.INVALID_ARGUMENT, self.client.load_definitions,
                         inline={"py_broken.proto": syntax_error}, contains=["py_broken.proto"])
        # Parses, but a DCCL field without bounds breaks a DCCL rule.
        unbounded = ('syntax = "proto2";\nimport "dccl/option_extensions.proto";\npackage pybad;\n'
                     'message Unbounded {\n  option (dccl.msg) = { codec_version: 4 id: 64 max_bytes: 8 };\n'
                     '  required int32 level = 1;\n}\n')
        self.assertFails(grpc.StatusCode.INVALID_ARGUMENT, self.client.load_definitions,
                         inline={"py_unbounded.proto": unbounded}, contains=["level"])
        self.assertFails(grpc.StatusCode.NOT_FOUND, self.client.submit, "pybad.Unbounded", {"level": 1})

    # ---------------------------------------------------------------- RESOURCE_EXHAUSTED

    def test_full_queue_that_refuses_new_is_resource_exhausted(self):
        first = self.client.submit("pytest.Beacon", {"seq": 1})
        self.assertGreater(first, 0)
        self.assertFails(grpc.StatusCode.RESOURCE_EXHAUSTED, self.client.submit, "pytest.Beacon", {"seq": 2},
                         contains=["pytest.Beacon"])
        self.assertEqual(self.queued_ids("pytest.Beacon"), [first])

    # ---------------------------------------------------------------- FAILED_PRECONDITION

    def test_set_cycle_on_mac_none_is_failed_precondition(self):
        self.assertFails(grpc.StatusCode.FAILED_PRECONDITION, self.client.set_cycle,
                         [{"src": 1, "seconds": 10}])

    # ---------------------------------------------------------------- the client itself

    def test_missing_socket_is_reported_before_any_call(self):
        error = self.assertFails(grpc.StatusCode.UNAVAILABLE, AcommsClient,
                                 os.path.join(self.dir, "nobody.sock"), contains=["no such socket"])
        self.assertIn("nobody.sock", str(error))

    def test_example_scripts(self):
        env = dict(os.environ, ACOMMS_PYTHON_GENERATED=GENERATED)

        def run(*args):
            return subprocess.run([sys.executable, *args], cwd=EXAMPLES_DIR, env=env, capture_output=True,
                                  text=True, timeout=30)

        ok = run("submit.py", "--socket", self.socket, "pytest.Report", '{"depth": 2}')
        self.assertEqual(ok.returncode, 0, ok.stderr)
        self.assertRegex(ok.stdout, r"^queued pytest.Report as message \d+\n$")
        bad = run("submit.py", "--socket", self.socket, "pytest.Report", '{"depth": -3}')
        self.assertEqual(bad.returncode, 1)
        self.assertIn("INVALID_ARGUMENT", bad.stderr)
        listen = run("subscribe.py", "--socket", self.socket, "--type", "pytest.Report", "--seconds", "0.5")
        self.assertEqual(listen.returncode, 0, listen.stderr)
        self.assertIn("0 messages received", listen.stderr)


def main():
    global ACOMMSD, GENERATED
    parser = argparse.ArgumentParser()
    parser.add_argument("--acommsd", required=True, help="the acommsd binary")
    parser.add_argument("--generated", required=True, help="where the Python stubs are generated")
    args, rest = parser.parse_known_args()
    ACOMMSD = os.path.abspath(args.acommsd)
    GENERATED = os.path.abspath(args.generated)
    generate_stubs(GENERATED)
    unittest.main(argv=[sys.argv[0], *rest], verbosity=2)


if __name__ == "__main__":
    main()
