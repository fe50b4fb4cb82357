"""The shortest path through the core: a program, a scan, an output."""

from plcsim import CPU, Tag


def test_button_drives_led_in_the_same_scan():
    cpu = CPU(tags={"TL": Tag("%I0.0"), "LED": Tag("%Q0.0")}, program="def OB1(t):\n    t.LED = t.TL\n")
    cpu.set_input("TL", True)
    cpu.scan()
    assert cpu.outputs["LED"] is True
    assert cpu.now == 1_000_000
