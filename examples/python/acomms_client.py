"""A small Python client for acommsd's gRPC API (acomms.v1.Acomms).

acommsd listens on a unix socket; this module opens a channel to it and
wraps the calls a vehicle program needs most, with messages given as dicts
(sent as JSON), serialized bytes or protobuf messages:

    from acomms_client import AcommsClient, AcommsError

    with AcommsClient("var/vehicle/acommsd.sock") as acomms:
        message_id = acomms.submit("example.Status", {"depth": 10})
        for received in acomms.subscribe(["example.Status"]):
            print(received.src, received.message)

Over TCP (a daemon with grpc.tcp_listen), the connection is TLS; with
grpc.tls.client_ca_file set, the client shows its own certificate too:

    acomms = AcommsClient("192.168.1.10:50051", tcp=True,
                          ca_file="/etc/acommsd/tls/ca.pem",       # trusts the daemon
                          cert_file="/etc/acommsd/tls/client.pem",  # mutual TLS only
                          key_file="/etc/acommsd/tls/client.key")

Every failed call raises AcommsError, which carries the gRPC status code
(grpc.StatusCode.NOT_FOUND, INVALID_ARGUMENT, RESOURCE_EXHAUSTED,
FAILED_PRECONDITION, UNAVAILABLE, ...) and the daemon's message, written for
a person (INVALID_ARGUMENT names the field and the bound it broke). See
api/proto/acomms/v1/acomms.proto for what each call answers.

The stubs are made by generate.sh. They are imported from the Python path
if they are there, else from $ACOMMS_PYTHON_GENERATED, else from the
`generated` directory beside this file.

Needs the system Python with Debian's python3-grpcio and python3-protobuf
(/usr/bin/python3).
"""

from __future__ import annotations

import json as _json
import os
import sys
import threading
from dataclasses import dataclass, field
from typing import Any, Dict, Iterable, Iterator, List, Mapping, Optional, Sequence, Union

import grpc
from google.protobuf import message as _pb_message


def _import_stubs():
    try:
        from acomms.v1 import acomms_pb2, acomms_pb2_grpc, config_pb2  # noqa: F401
    except ImportError:
        where = os.environ.get("ACOMMS_PYTHON_GENERATED") or os.path.join(
            os.path.dirname(os.path.abspath(__file__)), "generated")
        if where not in sys.path:
            sys.path.insert(0, where)
        try:
            from acomms.v1 import acomms_pb2, acomms_pb2_grpc, config_pb2  # noqa: F401,F811
        except ImportError as e:
            raise ImportError(
                f"acomms_client: the acomms.v1 Python stubs are not in {where}: "
                "run examples/python/generate.sh (or set ACOMMS_PYTHON_GENERATED)") from e
    return acomms_pb2, acomms_pb2_grpc, config_pb2


pb, pb_grpc, config_pb = _import_stubs()

DEFAULT_SOCKET = "/run/acommsd/acommsd.sock"

Message = Union[Mapping[str, Any], str, bytes, _pb_message.Message]


def default_socket() -> str:
    """$ACOMMSD_SOCKET, else the packaged daemon's socket."""
    return os.environ.get("ACOMMSD_SOCKET") or DEFAULT_SOCKET


class AcommsError(Exception):
    """A call to acommsd failed.

    code:    the grpc.StatusCode (e.g. grpc.StatusCode.NOT_FOUND)
    details: the daemon's message
    method:  the call that failed, e.g. "Submit"
    """

    def __init__(self, code: grpc.StatusCode, details: str, method: str = ""):
        self.code = code
        self.details = details or ""
        self.method = method
        where = f"{method}: " if method else ""
        super().__init__(f"{where}{code.name}: {self.details}")

    @classmethod
    def from_rpc_error(cls, error: grpc.RpcError, method: str = "") -> "AcommsError":
        code = error.code() if hasattr(error, "code") else grpc.StatusCode.UNKNOWN
        details = error.details() if hasattr(error, "details") else str(error)
        return cls(code, details, method)


@dataclass
class Received:
    """A message received from the link (acomms.v1.ReceivedMessage)."""

    type: str
    # The message as a dict (its JSON form, proto field names).
    message: Dict[str, Any]
    # The serialized protobuf of `type`.
    payload: bytes
    # Modem ids: source and destination (0: broadcast).
    src: int
    dest: int
    # Seconds since the Unix epoch.
    receive_time: float
    # What the modem reported about the transmission (acomms.v1.LinkFigures).
    link: Any = field(default=None, repr=False)

    @classmethod
    def from_proto(cls, received: "pb.ReceivedMessage") -> "Received":
        return cls(type=received.type,
                   message=_json.loads(received.json) if received.json else {},
                   payload=received.payload, src=received.src, dest=received.dest,
                   receive_time=received.receive_time, link=received.link)


class Subscription:
    """A Subscribe stream: iterate it for Received messages; cancel() (or
    leaving a `with` block) ends it, and the iteration then stops quietly.
    A stream the daemon ends (it stops: UNAVAILABLE; this subscriber fell too
    far behind: RESOURCE_EXHAUSTED) raises AcommsError."""

    def __init__(self, call):
        self._call = call
        self._cancelled = threading.Event()

    def __iter__(self) -> Iterator[Received]:
        try:
            for received in self._call:
                yield Received.from_proto(received)
        except grpc.RpcError as e:
            if self._cancelled.is_set() and e.code() == grpc.StatusCode.CANCELLED:
                return
            raise AcommsError.from_rpc_error(e, "Subscribe") from None

    def cancel(self) -> None:
        """Ends the stream; safe from any thread, and more than once."""
        self._cancelled.set()
        self._call.cancel()

    def is_active(self) -> bool:
        """True while the stream is open."""
        return self._call.is_active()

    def __enter__(self) -> "Subscription":
        return self

    def __exit__(self, *exc) -> None:
        self.cancel()


def _set_message(request, message: Message) -> None:
    """Puts `message` into a SubmitRequest or EncodeRequest: a protobuf
    message or bytes as the payload, a str as JSON, anything else (a dict)
    dumped to JSON."""
    if isinstance(message, _pb_message.Message):
        request.payload = message.SerializePartialToString()
    elif isinstance(message, (bytes, bytearray)):
        request.payload = bytes(message)
    elif isinstance(message, str):
        request.json = message
    else:
        request.json = _json.dumps(message)


def connect(socket: Optional[str] = None, timeout: Optional[float] = 10.0) -> "AcommsClient":
    """An AcommsClient on the unix socket `socket` (default: default_socket())."""
    return AcommsClient(socket, timeout)


def _read(path: Optional[str]) -> Optional[bytes]:
    if not path:
        return None
    with open(path, "rb") as f:
        return f.read()


class AcommsClient:
    """A connection to acommsd over its unix socket, or over TCP.

    socket:    the socket path; default $ACOMMSD_SOCKET or
               /run/acommsd/acommsd.sock. A "host:port" with tcp=True talks
               TCP to a daemon with grpc.tcp_listen set.
    timeout:   seconds each unary call may take (None: no limit).
    TCP only (the default is TLS, as the daemon's):
    ca_file:   PEM file of the CA that issued the daemon's certificate
               (default: the system's CAs).
    cert_file, key_file: this client's certificate and key, for a daemon
               with grpc.tls.client_ca_file (mutual TLS).
    insecure:  plaintext, only for a daemon with grpc.insecure_tcp: true.
    """

    def __init__(self, socket: Optional[str] = None, timeout: Optional[float] = 10.0,
                 tcp: bool = False, ca_file: Optional[str] = None, cert_file: Optional[str] = None,
                 key_file: Optional[str] = None, insecure: bool = False):
        self.socket = socket or default_socket()
        self.timeout = timeout
        if tcp:
            if bool(cert_file) != bool(key_file):
                raise ValueError("cert_file and key_file go together (mutual TLS)")
            if insecure:
                self._channel = grpc.insecure_channel(self.socket)
            else:
                credentials = grpc.ssl_channel_credentials(
                    root_certificates=_read(ca_file), private_key=_read(key_file),
                    certificate_chain=_read(cert_file))
                self._channel = grpc.secure_channel(self.socket, credentials)
        else:
            if not os.path.exists(self.socket):
                raise AcommsError(grpc.StatusCode.UNAVAILABLE,
                                  f"cannot reach acommsd at {self.socket}: no such socket "
                                  "(is acommsd running? see --socket / $ACOMMSD_SOCKET)")
            self._channel = grpc.insecure_channel("unix:" + os.path.abspath(self.socket))
        self.stub = pb_grpc.AcommsStub(self._channel)

    def close(self) -> None:
        self._channel.close()

    def __enter__(self) -> "AcommsClient":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def _call(self, method: str, request):
        try:
            return getattr(self.stub, method)(request, timeout=self.timeout)
        except grpc.RpcError as e:
            raise AcommsError.from_rpc_error(e, method) from None

    # ------------------------------------------------------------ status

    def status(self) -> "pb.Status":
        """Daemon identity and health (acomms.v1.Status)."""
        return self._call("GetStatus", pb.GetStatusRequest())

    # ------------------------------------------------------------ definitions

    def load_definitions(self, paths: Sequence[str] = (),
                         inline: Optional[Mapping[str, str]] = None,
                         include_dirs: Sequence[str] = ()) -> List["pb.TypeInfo"]:
        """Loads DCCL definitions: .proto files on the daemon's machine
        (`paths`) and/or sources sent along (`inline`: file name -> text).
        Returns the types they define."""
        request = pb.LoadDefinitionsRequest(paths=list(paths), include_dirs=list(include_dirs))
        for name, text in (inline or {}).items():
            request.inline.add(name=name, text=text)
        return list(self._call("LoadDefinitions", request).types)

    def list_types(self, types: Sequence[str] = (), fields: bool = False,
                   descriptors: bool = False) -> List["pb.TypeInfo"]:
        request = pb.ListTypesRequest(types=list(types), fields=fields, descriptors=descriptors)
        return list(self._call("ListTypes", request).types)

    # ------------------------------------------------------------ submit

    def submit(self, type: str, message: Message, ttl: float = 0.0) -> int:
        """Queues a message of DCCL type `type` and returns its durable id.

        message: a dict (sent as JSON), a JSON string, the serialized
                 protobuf (bytes), or a protobuf message of that type.
        ttl:     seconds it may wait in the queue; 0: the queue's ttl.
        """
        request = pb.SubmitRequest(type=type, ttl_s=ttl)
        _set_message(request, message)
        return self._call("Submit", request).message_id

    # ------------------------------------------------------------ subscribe

    def subscribe(self, types: Iterable[str] = (), src: Optional[int] = None) -> Subscription:
        """Messages received from the link, as they arrive: only of `types`
        (empty: every type) and only from modem id `src` (None: anyone).
        Iterate the returned Subscription; it has no timeout."""
        request = pb.SubscribeRequest(types=list(types))
        if src is not None:
            request.src = src
        return Subscription(self.stub.Subscribe(request))

    # ------------------------------------------------------------ queues

    def list_queued(self, type: str = "", limit: int = 0) -> List["pb.QueuedMessage"]:
        """Queued messages (of `type`; empty: every queue), at most `limit`
        (0: 1000)."""
        return list(self._call("ListQueued", pb.ListQueuedRequest(type=type, limit=limit)).messages)

    def cancel(self, message_id: int, reason: str = "") -> None:
        """Removes a queued message; NOT_FOUND if it is not queued."""
        self._call("Cancel", pb.CancelRequest(message_id=message_id, reason=reason))

    def flush(self, type: str) -> int:
        """Removes every message of `type`; returns how many."""
        return self._call("Flush", pb.FlushRequest(type=type)).removed

    def queue_stats(self, types: Sequence[str] = ()) -> List["pb.QueueStatsEntry"]:
        return list(self._call("QueueStats", pb.QueueStatsRequest(types=list(types))).queues)

    # ------------------------------------------------------------ link

    def link_status(self) -> "pb.LinkStatusResponse":
        return self._call("LinkStatus", pb.LinkStatusRequest())

    def set_cycle(self, slots: Sequence[Union[Mapping[str, Any], "config_pb.MacSlot"]]) -> float:
        """Replaces the MAC cycle from the next cycle boundary; slots are
        acomms.v1.MacSlot or dicts of its fields (src, dest, rate, seconds).
        Returns the new cycle's length in seconds."""
        request = pb.SetCycleRequest()
        for slot in slots:
            if isinstance(slot, _pb_message.Message):
                request.slot.add().CopyFrom(slot)
            else:
                request.slot.add(**slot)
        return self._call("SetCycle", request).cycle_seconds

    # ------------------------------------------------------------ events

    def events(self, since: float = 0, until: float = 0, kinds: Sequence[str] = (),
               types: Sequence[str] = (), message_id: int = 0, limit: int = 0) -> List["pb.Event"]:
        request = pb.EventsRequest(since=since, until=until, kinds=list(kinds), types=list(types),
                                   message_id=message_id, limit=limit)
        return list(self._call("Events", request).events)

    # ------------------------------------------------------------ helpers

    def encode(self, type: str, message: Message) -> bytes:
        """The DCCL bytes `message` encodes to, without queueing it."""
        request = pb.EncodeRequest(type=type)
        _set_message(request, message)
        return self._call("Encode", request).encoded

    def decode(self, encoded: bytes, type: str = "") -> List[Dict[str, Any]]:
        """Decodes DCCL bytes (one or more messages back to back); returns
        one {"type": ..., "message": dict} per message."""
        response = self._call("Decode", pb.DecodeRequest(encoded=encoded, type=type))
        return [{"type": m.type, "message": _json.loads(m.json) if m.json else {}}
                for m in response.messages]
