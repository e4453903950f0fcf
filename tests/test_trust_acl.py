"""Issue 44, "trust, completed": ACLs, the certificate cache, one read of the certificates, regular files only.

Each defect of the audit is a test that fails on the code before the fix:

1. A POSIX access ACL (``setfacl -m u:nobody:rw`` on the module and ``SHA256SUMS``) let another user rewrite a
   tree consistently while the mode bits looked private (``rw-rw-r--`` with the user's private group), and
   ``load_formulas(path=T)`` ran it.  The ACLs are written here as the binary extended attribute
   ``system.posix_acl_access`` (built with ``struct`` from the kernel's format, not with ``suslov.acl``);
   where the file system refuses it the test is skipped with the reason.  The parser is also tested on
   hand-built byte strings, and an ACL that cannot be read (EIO) must refuse, not trust.
2. A world-writable ``$SUSLOV_CACHE_DIR`` was trusted: ``load_formulas(pmax=N)`` started the build that installs
   from it.  The build is replaced here by a fake ``Popen`` that records whether it was started.
3. ``load_certificates()`` must parse the bytes the verification read: ``certificates.json`` is opened exactly
   once (counted with the interpreter's ``open`` audit event, which both ``open`` and ``os.open`` raise).
4. A FIFO as ``certificates.json``, ``SHA256SUMS`` or the module blocked ``load_formulas(path=T)`` forever (or
   was "not a generated tree"); it is refused with a ValueError naming the file.  Each load runs in a thread
   with a deadline; a blocked reader is released by opening the FIFO for writing, and the test fails.
"""
import errno
import hashlib
import json
import os
import shutil
import stat
import struct
import sys
import threading
from pathlib import Path

import pytest

from suslov import acl, loader, manifest
from suslov.manifest import MANIFEST, NotRegularFile, UntrustedCache, UntrustedTree

GENERATED = Path(__file__).resolve().parents[1] / "generated"
XATTR = "system.posix_acl_access"
NOBODY = 65534
posix_only = pytest.mark.skipif(os.name != "posix", reason="POSIX ownership, modes and ACLs")


def acl_bytes(*entries) -> bytes:
    """The Linux binary ACL: version 2 (u32 LE), then (tag u16, perm u16, id u32) LE per entry."""
    return struct.pack("<I", 2) + b"".join(struct.pack("<HHI", tag, perm, ident) for tag, perm, ident in entries)


UNDEFINED = 0xFFFFFFFF
# what `setfacl -m u:nobody:rw` leaves on a rw-r--r-- file: the owner rw, nobody rw, group r, mask rw, other r
NOBODY_RW = acl_bytes((0x01, 6, UNDEFINED), (0x02, 6, NOBODY), (0x04, 4, UNDEFINED), (0x10, 6, UNDEFINED),
                      (0x20, 4, UNDEFINED))
NOBODY_RWX = acl_bytes((0x01, 7, UNDEFINED), (0x02, 7, NOBODY), (0x04, 5, UNDEFINED), (0x10, 7, UNDEFINED),
                       (0x20, 5, UNDEFINED))


def acl_unsupported(directory: Path) -> str | None:
    """Why an access ACL cannot be set on files in ``directory`` here, or None."""
    if not hasattr(os, "setxattr"):
        return "os.setxattr does not exist on this platform"
    probe = directory / ".acl-probe"
    probe.write_bytes(b"")
    try:
        os.setxattr(probe, XATTR, NOBODY_RW)
        return None if os.getxattr(probe, XATTR) == NOBODY_RW else "the ACL read back differs"
    except OSError as error:
        return f"setxattr({XATTR}) failed: {error}"
    finally:
        probe.unlink()


@pytest.fixture
def acl_fs(tmp_path):
    why = acl_unsupported(tmp_path)
    if why:
        pytest.skip(f"POSIX ACLs cannot be set on {tmp_path}: {why}")
    return tmp_path


@pytest.fixture
def private_group(monkeypatch):
    """A user-private-group system (umask 002, every desktop Linux): the files' own group is the user's alone,
    so ``rw-rw-r--`` looks private -- the setting in which the ACL attack went through."""
    monkeypatch.setattr(manifest, "_private_group", lambda gid, uid: gid == os.getgid())


def remanifest(tree: Path) -> None:
    names = [line.split("  ", 1)[1] for line in (GENERATED / MANIFEST).read_text().splitlines()]
    (tree / MANIFEST).write_text("".join(f"{hashlib.sha256((tree / n).read_bytes()).hexdigest()}  {n}\n"
                                         for n in sorted(names)))


def consistent_copy(target: Path) -> Path:
    """The checkout's tree (the files its manifest lists), with a manifest written here (hashlib)."""
    target.mkdir(parents=True)
    for line in (GENERATED / MANIFEST).read_text().splitlines():
        name = line.split("  ", 1)[1]
        shutil.copyfile(GENERATED / name, target / name)
    remanifest(target)
    return target


def rewrite_as_attacker(tree: Path, sentinel: Path) -> None:
    """What the user the ACL lets in does: a line that runs at import, and a manifest that matches again."""
    with open(tree / "suslov_formulas.py", "a") as handle:
        handle.write(f"\nopen({str(sentinel)!r}, 'w').write('ran')\n")
    remanifest(tree)


# ---------------------------------------------------------------- 1. the ACL parser, on hand-built bytes


def test_parser_reads_entries_and_applies_the_mask():
    entries = acl.parse(NOBODY_RW)
    assert [(e.tag, e.perm, e.id) for e in entries] == [(1, 6, UNDEFINED), (2, 6, NOBODY), (4, 4, UNDEFINED),
                                                        (0x10, 6, UNDEFINED), (0x20, 4, UNDEFINED)]
    assert [(e.tag, e.id) for e in acl.writers(entries)] == [(acl.USER, NOBODY)]
    # the mask limits named users and groups and the owning group, not the owner or other
    masked = acl.parse(acl_bytes((1, 6, UNDEFINED), (2, 6, NOBODY), (4, 6, UNDEFINED), (8, 6, 1234),
                                 (0x10, 4, UNDEFINED), (0x20, 4, UNDEFINED)))
    assert acl.writers(masked) == []
    other = acl.parse(acl_bytes((1, 6, UNDEFINED), (4, 4, UNDEFINED), (0x10, 0, UNDEFINED), (0x20, 6, UNDEFINED)))
    assert [e.tag for e in acl.writers(other)] == [acl.OTHER]
    # a minimal ACL (no mask): the group entry counts as written
    minimal = acl.parse(acl_bytes((1, 6, UNDEFINED), (4, 6, UNDEFINED), (0x20, 4, UNDEFINED)))
    assert [e.tag for e in acl.writers(minimal)] == [acl.GROUP_OBJ]
    named_group = acl.parse(acl_bytes((1, 7, UNDEFINED), (4, 5, UNDEFINED), (8, 2, 4321), (0x10, 7, UNDEFINED),
                                      (0x20, 5, UNDEFINED)))
    assert [(e.tag, e.id) for e in acl.writers(named_group)] == [(acl.GROUP, 4321)]


@pytest.mark.parametrize("data, why", [
    (b"", "0 bytes"),
    (b"\x02\x00\x00", "3 bytes"),
    (NOBODY_RW + b"\x00", "is not a 4-byte header"),
    (struct.pack("<I", 1) + NOBODY_RW[4:], "version 1"),
    (acl_bytes((1, 6, UNDEFINED), (0x40, 6, 7)), "unknown entry tag 0x40"),
])
def test_parser_refuses_malformed_acls(data, why):
    with pytest.raises(acl.AclError, match=why):
        acl.parse(data)


@pytest.mark.parametrize("code, verdict", [("ENODATA", None), ("ENOTSUP", None), ("EOPNOTSUPP", None),
                                           ("EACCES", "unreadable"), ("EIO", "unreadable")])
def test_only_no_attribute_or_no_support_mean_no_acl(monkeypatch, tmp_path, code, verdict):
    if not acl.supported():
        pytest.skip("os.getxattr does not exist on this platform")
    number = getattr(errno, code)

    def getxattr(target, name):
        raise OSError(number, os.strerror(number))

    monkeypatch.setattr(acl.os, "getxattr", getxattr)
    if verdict is None:
        assert acl.access_acl(tmp_path) is None
    else:
        with pytest.raises(acl.AclUnreadable, match="cannot be read"):
            acl.access_acl(tmp_path)


# ---------------------------------------------------------------- 1. trees with ACLs are refused


@posix_only
def test_the_audit_attack_an_acl_on_module_and_manifest_is_refused(acl_fs, private_group, forget_loaded):
    tree = consistent_copy(acl_fs / "tree")
    for name in ("suslov_formulas.py", MANIFEST):
        os.setxattr(tree / name, XATTR, NOBODY_RW)
    mode = (tree / "suslov_formulas.py").stat().st_mode
    assert not mode & stat.S_IWOTH   # the mode bits look private (rw-rw-r--, the user's own group)
    sentinel = acl_fs / "ran"
    rewrite_as_attacker(tree, sentinel)
    with pytest.raises(UntrustedTree) as caught:
        loader.load_formulas(path=tree)
    message = str(caught.value)
    assert f"user id {NOBODY}" in message and "ACL" in message and "setfacl -b" in message
    assert str(tree / MANIFEST) in message or str(tree / "suslov_formulas.py") in message
    assert not sentinel.exists()


@posix_only
@pytest.mark.parametrize("where", ["tree", "certificates", "parent"])
def test_an_acl_on_the_directory_a_file_or_a_parent_is_refused(acl_fs, private_group, where):
    parent = acl_fs / "shared"
    tree = consistent_copy(parent / "tree")
    victim = {"tree": tree, "certificates": tree / "certificates.json", "parent": parent}[where]
    os.setxattr(victim, XATTR, NOBODY_RWX if victim.is_dir() else NOBODY_RW)
    with pytest.raises(UntrustedTree, match=f"{victim}.*writable by user id {NOBODY} through its POSIX access ACL"):
        manifest.verify(tree)
    if where == "parent":   # a sticky parent (as /tmp) may be written by others, by mode or by ACL
        parent.chmod(parent.stat().st_mode | stat.S_ISVTX)
        assert "suslov_formulas.py" in manifest.verify(tree)


@posix_only
def test_an_acl_granting_only_the_owner_and_root_is_accepted(acl_fs, private_group):
    tree = consistent_copy(acl_fs / "tree")
    own = acl_bytes((1, 6, UNDEFINED), (2, 6, os.getuid()), (2, 6, 0), (4, 4, UNDEFINED), (0x10, 6, UNDEFINED),
                    (0x20, 4, UNDEFINED))
    os.setxattr(tree / "suslov_formulas.py", XATTR, own)
    # and a named user whose write the mask takes away
    os.setxattr(tree / MANIFEST, XATTR, acl_bytes((1, 6, UNDEFINED), (2, 6, NOBODY), (4, 4, UNDEFINED),
                                                  (0x10, 4, UNDEFINED), (0x20, 4, UNDEFINED)))
    assert set(manifest.verify(tree)) >= set(manifest.REQUIRED)


@posix_only
def test_an_acl_that_cannot_be_read_refuses_the_tree(tmp_path, monkeypatch):
    if not acl.supported():
        pytest.skip("os.getxattr does not exist on this platform")
    tree = consistent_copy(tmp_path / "tree")
    real = os.getxattr

    def getxattr(target, name, *args, **kwargs):
        if name == XATTR and isinstance(target, int) and os.path.samestat(os.fstat(target),
                                                                            os.stat(tree / "suslov_formulas.py")):
            raise OSError(errno.EIO, os.strerror(errno.EIO))
        return real(target, name, *args, **kwargs)

    monkeypatch.setattr(acl.os, "getxattr", getxattr)
    with pytest.raises(UntrustedTree, match=r"suslov_formulas\.py: its access ACL .* cannot be read: "
                                            r"Input/output error .* who may write it is unknown"):
        manifest.verify(tree)


# ---------------------------------------------------------------- 2. the certificate cache


@pytest.fixture
def no_build(monkeypatch, tmp_path):
    """load_formulas(pmax=N) beyond every stored module, with the build replaced by a recorder."""
    started = []

    class Started(Exception):
        pass

    def popen(command, *args, **kwargs):
        started.append(command)
        raise Started(command)

    monkeypatch.setattr(loader.subprocess, "Popen", popen)
    monkeypatch.setattr(loader, "require", lambda extra, what: None)
    monkeypatch.setenv(loader.DATA_ENV, str(tmp_path / "store"))
    monkeypatch.delenv(loader.NO_CACHE_ENV, raising=False)
    pmax = loader.active_formulas().PMAX + 2

    def load():
        loader.load_formulas(pmax=pmax, quiet=True)

    load.started, load.Started = started, Started
    return load


def private_cache(tmp_path, monkeypatch) -> Path:
    cache = tmp_path / "cache"
    (cache / "builds" / "0123abcd").mkdir(parents=True, mode=0o755)
    (cache / "builds" / "0123abcd" / "suslov_formulas.py").write_text("x = 1\n")
    (cache / "per-p").mkdir(mode=0o755)
    monkeypatch.setenv(loader.CACHE_ENV, str(cache))
    return cache


@posix_only
@pytest.mark.parametrize("where", ["root", "inside", "file"])
def test_a_cache_others_can_write_is_refused_before_the_build(tmp_path, monkeypatch, no_build, where):
    cache = private_cache(tmp_path, monkeypatch)
    victim = {"root": cache, "inside": cache / "builds", "file": cache / "builds/0123abcd/suslov_formulas.py"}[where]
    victim.chmod(victim.stat().st_mode | stat.S_IWOTH)
    with pytest.raises(UntrustedCache) as caught:
        no_build()
    message = str(caught.value)
    assert isinstance(caught.value, ValueError) and "\n" not in message
    assert message.startswith(f"$SUSLOV_CACHE_DIR {cache}:") and str(victim) in message
    assert "writable by every user" in message and f"chmod go-w {victim}" in message
    assert no_build.started == []


@posix_only
def test_a_cache_with_an_acl_is_refused(acl_fs, monkeypatch, no_build):
    cache = private_cache(acl_fs, monkeypatch)
    os.setxattr(cache, XATTR, NOBODY_RWX)
    with pytest.raises(UntrustedCache, match=f"{cache}: it is writable by user id {NOBODY} through its POSIX"):
        no_build()
    assert no_build.started == []


@posix_only
def test_a_private_cache_or_none_lets_the_build_start(tmp_path, monkeypatch, no_build):
    cache = private_cache(tmp_path, monkeypatch)
    with pytest.raises(no_build.Started):
        no_build()
    monkeypatch.setenv(loader.CACHE_ENV, str(tmp_path / "not-yet" / "cache"))   # created by the build
    with pytest.raises(no_build.Started):
        no_build()
    cache.chmod(cache.stat().st_mode | stat.S_IWOTH)   # shared, but the build will not use it
    monkeypatch.setenv(loader.CACHE_ENV, str(cache))
    monkeypatch.setenv(loader.NO_CACHE_ENV, "1")
    with pytest.raises(no_build.Started):
        no_build()
    assert len(no_build.started) == 3


# ---------------------------------------------------------------- 3. one read of certificates.json


def test_certificates_json_is_read_once_and_that_read_is_what_load_certificates_parses(tmp_path, forget_loaded):
    tree = consistent_copy(tmp_path / "tree")
    target = str(tree / "certificates.json")
    opened, counting = [], [False]

    def hook(event, args):
        if counting[0] and event == "open" and args and str(args[0]) == target:
            opened.append(args)

    sys.addaudithook(hook)   # cannot be removed: it counts only while the flag is set
    counting[0] = True
    try:
        module = loader.load_formulas(path=tree)
        document = module.load_certificates()
    finally:
        counting[0] = False
    assert len(opened) == 1, opened
    assert manifest.verified_files(module)["certificates.json"] is module.load_certificates.verified_bytes
    assert document == json.loads((GENERATED / "certificates.json").read_bytes())


def test_verify_returns_the_bytes_of_every_listed_file(tmp_path):
    tree = consistent_copy(tmp_path / "tree")
    contents = manifest.verify(tree)
    listed = manifest.read(tree)
    assert set(contents) == set(listed)
    assert all(hashlib.sha256(contents[name]).hexdigest() == listed[name] for name in listed)


# ---------------------------------------------------------------- 4. regular files only


def finishes(call, fifos, seconds=60):
    """Run ``call`` in a thread; the exception it raised, or fail (after releasing a reader blocked on a FIFO)."""
    outcome = {}

    def run():
        try:
            call()
        except BaseException as error:   # noqa: BLE001 - handed to the test
            outcome["error"] = error

    thread = threading.Thread(target=run, daemon=True)
    thread.start()
    thread.join(seconds)
    if thread.is_alive():
        for fifo in fifos:   # a blocked open(O_RDONLY) returns once a writer opens; then EOF
            try:
                os.close(os.open(fifo, os.O_WRONLY | os.O_NONBLOCK))
            except OSError:
                pass
        thread.join(10)
        pytest.fail(f"still blocked after {seconds} s on a FIFO: {fifos}")
    return outcome.get("error")


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs on this platform")
@pytest.mark.parametrize("name", ["certificates.json", MANIFEST, "suslov_formulas.py"])
def test_a_fifo_in_the_tree_is_refused_not_waited_on(tmp_path, forget_loaded, name):
    tree = consistent_copy(tmp_path / "tree")
    (tree / name).unlink()
    os.mkfifo(tree / name, 0o600)
    error = finishes(lambda: loader.load_formulas(path=tree), [tree / name])
    assert isinstance(error, NotRegularFile) and isinstance(error, ValueError), repr(error)
    assert f"{tree / name}: is a FIFO (named pipe)" in str(error) and "not a regular file" in str(error)


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs on this platform")
def test_a_fifo_in_a_store_entry_is_refused_not_waited_on(tmp_path, monkeypatch, forget_loaded):
    store = tmp_path / "store"
    entry = consistent_copy(store / "pmax-99")
    (entry / "certificates.json").unlink()
    os.mkfifo(entry / "certificates.json", 0o600)
    monkeypatch.setenv(loader.DATA_ENV, str(store))
    error = finishes(lambda: loader.load_formulas(pmax=99, build=False), [entry / "certificates.json"])
    assert isinstance(error, NotRegularFile) and str(entry / "certificates.json") in str(error), repr(error)


def test_read_regular_refuses_devices_and_directories(tmp_path):
    with pytest.raises(NotRegularFile, match="is a directory"):
        manifest.read_regular(tmp_path)
    if os.path.exists("/dev/null"):
        with pytest.raises(NotRegularFile, match="/dev/null: is a character device"):
            manifest.read_regular("/dev/null")
    (tmp_path / "f").write_bytes(b"abc")
    assert manifest.read_regular(tmp_path / "f") == b"abc"
