"""Buggy: the ON contact outside the series NC contact, LED := TLACIDLO_ZAP OR (LED AND NOT TLACIDLO_VYP):
with both buttons pressed the LED lights."""


def OB1(t):
    t.LED = t.TLACIDLO_ZAP or (t.LED and not t.TLACIDLO_VYP)
