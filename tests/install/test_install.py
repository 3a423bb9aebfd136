#!/usr/bin/env python3
"""`cmake --install` into a temporary prefix, then the installed binary: `--version` runs
(the engine's shared library is found beside it, in PREFIX/lib) and `serve` serves its page
from PREFIX/share/cloudgraph/web, not from the source tree (moved out of reach by a
CLOUDGRAPH_WEB_DIR-free environment and a page file that only the install holds)."""

import argparse
import os
import pathlib
import subprocess
import sys
import tempfile
import urllib.request


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--cmake", required=True)
    parser.add_argument("--build", required=True)
    parser.add_argument("--graph", required=True)
    args = parser.parse_args()

    with tempfile.TemporaryDirectory(prefix="cloudgraph-install-") as tmp:
        prefix = pathlib.Path(tmp) / "prefix"
        subprocess.run([args.cmake, "--install", args.build, "--prefix", str(prefix)],
                       check=True, stdout=subprocess.DEVNULL)
        binary = prefix / "bin" / "cloudgraph"
        env = {k: v for k, v in os.environ.items() if k != "CLOUDGRAPH_WEB_DIR"}
        version = subprocess.run([str(binary), "--version"], env=env, check=True,
                                 capture_output=True, text=True).stdout
        assert "cloudgraph" in version, version
        # A file only the installed page folder has: served, so that folder is the one used.
        marker = prefix / "share" / "cloudgraph" / "web" / "installed-marker.txt"
        marker.write_text("installed\n")

        server = subprocess.Popen(
            [str(binary), "serve", args.graph, "--port", "0", "--out", str(pathlib.Path(tmp) / "out")],
            env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        try:
            line = server.stdout.readline()
            assert "http://127.0.0.1:" in line, line
            url = line.split(" at ")[1].split()[0]
            page = urllib.request.urlopen(url, timeout=30).read().decode()
            assert "<html" in page.lower(), page[:200]
            served = urllib.request.urlopen(url + "installed-marker.txt", timeout=30).read()
            assert served == b"installed\n", served
        finally:
            server.terminate()
            server.wait(timeout=30)
    print("installed cloudgraph serves its page from PREFIX/share/cloudgraph/web")
    return 0


if __name__ == "__main__":
    sys.exit(main())
