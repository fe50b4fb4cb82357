"""OB1's merged networks read their tags from the tag dict: the same rows as network by network.

The merge (one function for all of OB1's networks, :func:`plcsim.frontends.python.merge.merge_networks`) is the hot path
of every scan; :func:`plcsim.frontends.python.merge.read_root_directly` lets it read ``_t_dict["S1"]`` instead of the
attribute ``_t.S1``. Both must compute what the networks compute one by one.
"""

from __future__ import annotations

import dis

import plcsim.frontends.python.pipeline
from benchmarks import workload
from plcsim import CPU, Int, Tag
from plcsim.sim.recorder import Recorder


def _digest(scans: int) -> str:
    cpu = workload.new_cpu()
    recorder = Recorder(cpu)
    recorder.attach()
    for changes in workload.build_schedule(scans):
        if changes:
            cpu.inputs.update(changes)
        cpu.scan()
    assert cpu.scan_count == scans
    return recorder.trace.digest()


def test_the_merged_ob1_reads_tags_from_the_dict_and_never_through_the_tag_object():
    cpu = workload.new_cpu()
    merged = cpu._ob1.merged
    assert merged is not None and merged.__name__ == "_merged_OB1"
    ops = list(dis.get_instructions(merged))
    root_attrs = [i.argval for k, i in enumerate(ops[1:], 1) if i.opname == "LOAD_ATTR" and ops[k - 1].argval == "_t"]
    assert root_attrs == ["__dict__"]  # the one hoist: _t_dict = _t.__dict__, no guard call
    assert "_tags_of" not in {i.argval for i in ops}
    reads = [i.argval for k, i in enumerate(ops[1:], 1) if i.opname == "LOAD_CONST" and ops[k - 1].argval == "_t_dict"]
    assert {"I0", "Q0", "T1", "C1", "Level"} <= set(reads)


def test_merged_and_network_by_network_give_the_same_trace(monkeypatch):
    merged = _digest(3000)
    # no merge: each network is called
    monkeypatch.setattr(plcsim.frontends.python.pipeline, "MAX_MERGED_STATEMENTS", 0)
    assert workload.new_cpu()._ob1.merged is None
    assert _digest(3000) == merged


def test_a_merged_network_that_fails_names_its_own_line():
    source = "def n1(t):\n    t.A = t.B\n\ndef n2(t):\n    t.N = 10 // t.Z\n\nOB1 = [n1, n2]\n"
    tags = {"A": Tag("%Q0.0"), "B": Tag("%I0.0"), "N": Tag("%MW10", Int), "Z": Tag("%MW12", Int)}
    cpu = CPU(tags, source)
    assert cpu._ob1.merged is not None
    cpu.scan()
    assert cpu.mode == "STOP"
    assert "OB1 network 2 (n2), line 5: ZeroDivisionError" in cpu.error.message
