"""cmake --install ... --component python: the installed package imports without the build tree's PYTHONPATH and
reads the copy of data/ installed inside it (python/CMakeLists.txt, python/skinspec/__init__.py)."""
import os
import subprocess
import sys
import textwrap


def test_installed_package_uses_its_own_data(tmp_path):
    build = os.environ["SKINSPEC_BUILD_DIR"]
    subprocess.run(["cmake", "--install", build, "--component", "python", "--prefix", str(tmp_path)], check=True, capture_output=True)
    site = [os.path.join(root) for root, dirs, files in os.walk(tmp_path) if "skinspec" in dirs and root.endswith("dist-packages")]
    assert len(site) == 1
    script = textwrap.dedent("""
        import os, skinspec
        print(os.path.dirname(skinspec.__file__))
        print(skinspec.data_directory())
        print(skinspec.spectrum("biospec-lightly", [550], rays=1000).R[0])
    """)
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "SKINSPEC_DATA_DIR")}
    env["PYTHONPATH"] = site[0]
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, env=env, cwd=tmp_path, check=True)
    package, data, r = done.stdout.split("\n")[:3]
    assert package == os.path.join(site[0], "skinspec")
    assert data == os.path.join(package, "data")
    assert 0.0 < float(r) < 1.0


def test_virtual_environment_with_system_site_packages(tmp_path):
    """scripts/python_venv.sh: a venv made with --system-site-packages imports skinspec (its own copy) and numpy."""
    source = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    venv = tmp_path / "venv"
    subprocess.run(["bash", os.path.join(source, "scripts", "python_venv.sh"), str(venv), "--without-pip"], check=True, capture_output=True)
    script = textwrap.dedent("""
        import sys, numpy, skinspec
        print(sys.prefix)
        print(skinspec.__file__)
        r = skinspec.spectrum("biospec-lightly", [500, 600], rays=1000).R
        print(type(r).__name__, r.shape[0])
    """)
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "SKINSPEC_DATA_DIR")}
    done = subprocess.run([str(venv / "bin" / "python"), "-c", script], capture_output=True, text=True, env=env, cwd=tmp_path, check=True)
    prefix, package, arrays = done.stdout.split("\n")[:3]
    assert prefix == str(venv)
    assert package.startswith(str(venv))
    assert arrays == "ndarray 2"
    # Run again on the same environment: it is updated, not refused.
    subprocess.run(["bash", os.path.join(source, "scripts", "python_venv.sh"), str(venv)], check=True, capture_output=True)
