# configs.py: the configuration lists of bench/mutation (configs.txt, quick_configs.txt) as (family, pairs), and
# their Verilator -G arguments as rtl/models.cmake writes them (DEPTH is the RTL's Depth).
import re


def read(path):
    out = []
    with open(path) as f:
        for line in f:
            line = line.strip()
            if line and not line.startswith("#"):
                family, pairs = line.split("|")
                out.append((family, pairs.strip()))
    return out


def gargs(pairs):
    kv = re.findall(r"([A-Za-z][A-Za-z0-9]*) (-?[0-9]+)", pairs)
    return [f"-G{'Depth' if k == 'DEPTH' else k}={v}" for k, v in kv]


def top(family):
    return "voxcd_axi" if family == "axi" else "voxcd_device"
