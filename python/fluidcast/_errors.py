"""fluidcast.Error: a failed libfluidcast call, with its fc_code and message."""

from ._enums import Code


class Error(Exception):
    """A libfluidcast call failed.

    Attributes:
        code: the :class:`Code` (fc_code) the call returned; a plain int for a
            code this binding does not know.
        message: the library's reason. A rejection by the server (codes 1..99)
            carries the server's message, prefixed ``"server: "``.

    After ``Code.CLOSED``, ``Code.PROTOCOL`` or ``Code.IO`` the connection is
    unusable (later calls fail with ``Code.CLOSED``): close the client and
    connect again. A server error (1..99) leaves the connection usable unless
    the server closed it.
    """

    def __init__(self, code, message):
        try:
            code = Code(code)
        except ValueError:
            code = int(code)
        super().__init__(code, message)
        self.code = code
        self.message = message

    def __str__(self):
        name = self.code.name if isinstance(self.code, Code) else "code %d" % self.code
        return "%s: %s" % (name, self.message)


def raise_for(code, err):
    """Raises Error from an fc_code and the fc_error the call filled; nothing for FC_OK."""
    if code == Code.OK:
        return
    message = err.message.decode("utf-8", "replace") if err is not None else ""
    # The library fills err with the code it returns; trust the return value.
    raise Error(code, message or "(no message)")
