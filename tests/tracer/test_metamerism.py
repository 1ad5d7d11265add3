"""The README's metamerism example, as physics: the measured patch and its three-primary match render
as one colour under D65 and visibly apart under FL11 (and CIE A)."""

from demo.metamerism import delta_e, metamer_pair, render


def test_paints_match_in_daylight_and_part_under_a_fluorescent_tube():
    measured, mixed = metamer_pair()
    assert measured.kind == "measured" and mixed.kind == "tabulated"
    assert delta_e(render("D65", resolution=(64, 32), samples=16)) < 0.5
    assert delta_e(render("FL11", resolution=(64, 32), samples=16)) > 5.0
    assert delta_e(render("A", resolution=(64, 32), samples=16)) > 3.0
