"""Who a POSIX access ACL lets write a file or directory (issue 44: trust beyond the mode bits).

``setfacl -m u:nobody:rw FILE`` gives another user write access while ``ls -l`` shows little: the group
bits of the mode become the ACL's mask, and on a system with user-private groups (umask 002) a
group-writable mode is accepted by :mod:`suslov.manifest`.  So the trust check reads the access ACL
itself, the extended attribute ``system.posix_acl_access`` in the Linux binary format:

* a 4-byte little-endian version (2), then 8-byte entries ``(tag u16, perm u16, id u32)``;
* tags :data:`USER_OBJ` (the owner), :data:`USER` (a named user), :data:`GROUP_OBJ` (the owning group),
  :data:`GROUP` (a named group), :data:`MASK` (the most any USER, GROUP_OBJ or GROUP entry grants),
  :data:`OTHER`; permission bit 2 is write.

:func:`access_acl` reads it (``None``: no ACL -- ENODATA, or a file system without ACLs -- ENOTSUP);
any other failure is :class:`AclUnreadable`, which the trust check turns into a refusal: an ACL that
cannot be read could grant anything.  :func:`parse` and :func:`writers` are pure functions of the bytes.
Python offers ``os.getxattr`` on Linux only; elsewhere (macOS, the BSDs) no ACL is read here, as
``docs/trust.md`` says.  Standard library only (imported by the loader before NumPy).
"""
from __future__ import annotations

import errno
import os
import struct
from typing import NamedTuple

__all__ = ["GROUP", "GROUP_OBJ", "MASK", "OTHER", "USER", "USER_OBJ", "WRITE", "XATTR", "AclError", "AclUnreadable",
           "Entry", "access_acl", "parse", "supported", "writers"]

XATTR = "system.posix_acl_access"
VERSION = 2                      # POSIX_ACL_XATTR_VERSION
USER_OBJ, USER, GROUP_OBJ, GROUP, MASK, OTHER = 0x01, 0x02, 0x04, 0x08, 0x10, 0x20
WRITE = 0x02
TAG_NAMES = {USER_OBJ: "owner", USER: "user", GROUP_OBJ: "owning group", GROUP: "group", MASK: "mask",
             OTHER: "other"}
_HEADER, _ENTRY = struct.Struct("<I"), struct.Struct("<HHI")
# errors that mean "this file has no access ACL": none set, or a file system that has no ACLs at all
_NO_ACL = {getattr(errno, name) for name in ("ENODATA", "ENOATTR", "ENOTSUP", "EOPNOTSUPP") if hasattr(errno, name)}


class Entry(NamedTuple):
    tag: int
    perm: int
    id: int   # 0xffffffff (ACL_UNDEFINED_ID) for USER_OBJ, GROUP_OBJ, MASK, OTHER


class AclError(ValueError):
    """An access ACL that cannot be parsed."""


class AclUnreadable(OSError):
    """The access ACL exists (or may) but cannot be read; the caller refuses rather than trusting."""


def parse(data: bytes) -> list[Entry]:
    """The entries of a binary ``system.posix_acl_access`` value; :class:`AclError` names what is wrong."""
    if len(data) < _HEADER.size or (len(data) - _HEADER.size) % _ENTRY.size:
        raise AclError(f"{len(data)} bytes is not a 4-byte header plus 8-byte entries")
    (version,) = _HEADER.unpack_from(data)
    if version != VERSION:
        raise AclError(f"version {version}, expected {VERSION}")
    entries = [Entry(*_ENTRY.unpack_from(data, offset)) for offset in range(_HEADER.size, len(data), _ENTRY.size)]
    unknown = sorted({e.tag for e in entries} - set(TAG_NAMES))
    if unknown:
        # an entry we cannot interpret might grant write: never guess
        raise AclError(f"unknown entry tag {', '.join(hex(t) for t in unknown)}")
    return entries


def writers(entries: list[Entry]) -> list[Entry]:
    """The entries other than the owner's that grant write once the mask is applied.

    The mask limits named users and groups and the owning group (POSIX.1e); it does not limit the owner
    or other.  Without a mask entry (a minimal ACL, the mode bits alone) nothing is limited.
    """
    mask = next((e.perm for e in entries if e.tag == MASK), None)
    found = []
    for entry in entries:
        if entry.tag in (USER_OBJ, MASK):
            continue
        perm = entry.perm & mask if mask is not None and entry.tag in (USER, GROUP_OBJ, GROUP) else entry.perm
        if perm & WRITE:
            found.append(entry)
    return found


def supported() -> bool:
    """True where Python can read extended attributes (Linux); elsewhere ACLs are not inspected."""
    return hasattr(os, "getxattr")


def access_acl(target) -> list[Entry] | None:
    """The access ACL of ``target`` (a path or an open file descriptor), or None when it has none.

    Raises :class:`AclUnreadable` when the attribute cannot be read for another reason (EACCES, EIO, ...)
    and :class:`AclError` when it cannot be parsed: a refusal, not a silent "no ACL".
    """
    if not supported():
        return None
    try:
        data = os.getxattr(target, XATTR)
    except OSError as error:
        if error.errno in _NO_ACL:
            return None
        raise AclUnreadable(error.errno, f"its access ACL ({XATTR}) cannot be read: {error.strerror or error}") \
            from None
    return parse(data)
