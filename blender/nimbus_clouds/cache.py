# Where the VDB files go: //nimbus_cache/ beside a saved .blend, else a cache folder of the user's.
import os
import tempfile

import bpy


def user_cache_folder():
    """$XDG_CACHE_HOME/nimbus-blender (~/.cache/...; on Windows %LOCALAPPDATA%), else under bpy.app.tempdir."""
    root = os.environ.get("XDG_CACHE_HOME") or os.environ.get("LOCALAPPDATA") or os.path.join(
        os.path.expanduser("~"), ".cache")
    if root and os.path.isabs(root):
        return os.path.join(root, "nimbus-blender")
    return os.path.join(bpy.app.tempdir or tempfile.gettempdir(), "nimbus_cache")


def cache_folder():
    """The folder for this .blend's clouds (absolute): //nimbus_cache/ when saved, else the user's cache."""
    if bpy.data.filepath:
        return bpy.path.abspath("//nimbus_cache/")
    return user_cache_folder()


def ensure_folder():
    """cache_folder(), created; OSError naming it when it cannot be."""
    folder = cache_folder()
    try:
        os.makedirs(folder, exist_ok=True)
    except OSError as e:
        raise OSError(f"cache folder {folder}: {e.strerror or e}") from None
    if not os.access(folder, os.W_OK):
        raise OSError(f"cache folder {folder}: not writable")
    return folder


def blend_path(path):
    """path as the Volume should store it: relative (//...) for files beside a saved .blend."""
    if bpy.data.filepath:
        try:
            return bpy.path.relpath(path)
        except ValueError:  # another drive (Windows)
            return path
    return path
