//! Smell sensors (§7.1, §7.2): hand-computed receptor values for eq. 25/26, occlusion by
//! opaque walls, saturation, inhibition by whiskers (§7.3) and smell that follows the food
//! left.

use crate::sim_common::{assert_close, put, world, Still};

/// A rose: food at a point with odour ⟨1, 0, …, 0, 0.5⟩ and intensity 0.8, at (100, 100).
fn rose_world(extra_kind: &str, extra: &str, creature: &str) -> String {
    format!(
        r#"
[world.kinds.rose]
class = "food"
odour = [1, 0, 0, 0, 0, 0, 0, 0.5]
intensity = 0.8
{extra_kind}

[[world.objects]]
kind = "rose"
position = [100, 100]

{extra}

[creature]
{creature}
"#
    )
}

#[test]
fn receptor_reads_eq25_at_body_centre_when_whiskers_have_no_length() {
    // s = 0 puts both receptors at the body centre: d = 10, c = 0.01,
    // I = 0.8 / (1 + 0.01 * 100) = 0.4; receptor 1 = 0.4 * 1, receptor 8 = 0.4 * 0.5.
    let mut w = world(&rose_world("", "", "whisker_length = 0"), 1, 1);
    put(&mut w, 0, 110.0, 100.0, 0.0);
    w.step(&mut [Still]);
    let c = &w.creatures()[0];
    for side in 0..2 {
        assert_close(c.smell[side][0], 0.4, "receptor 1");
        assert_close(c.smell[side][7], 0.2, "receptor 8");
        assert_eq!(c.smell[side][1..7], [0.0; 6]);
    }
    // The observation starts with the 8 left receptors, then the 8 right ones.
    let obs = w.observation(0);
    assert_close(obs[0], 0.4, "smell_left_1");
    assert_close(obs[7], 0.2, "smell_left_8");
    assert_close(obs[8], 0.4, "smell_right_1");
    assert_close(obs[15], 0.2, "smell_right_8");
}

#[test]
fn receptors_sit_at_the_whisker_tips() {
    // φ = 90°, s = 5, facing +x from (100, 100): the left tip is at (100, 95), 15 LU from the
    // rose at (100, 80); the right tip at (100, 105), 25 LU away.
    let text = rose_world("", "", "whisker_angle = 90")
        .replace("position = [100, 100]", "position = [100, 80]");
    let mut w = world(&text, 1, 2);
    put(&mut w, 0, 100.0, 100.0, 0.0);
    w.step(&mut [Still]);
    let c = &w.creatures()[0];
    assert_close(c.smell[0][0], 0.8 / (1.0 + 0.01 * 225.0), "left receptor 1");
    assert_close(
        c.smell[1][0],
        0.8 / (1.0 + 0.01 * 625.0),
        "right receptor 1",
    );
    let tips = w.whisker_tips(0);
    assert!((tips[0].x - 100.0).abs() < 1e-12 && (tips[0].y - 95.0).abs() < 1e-12);
    assert!((tips[1].x - 100.0).abs() < 1e-12 && (tips[1].y - 105.0).abs() < 1e-12);
}

#[test]
fn smell_is_zero_at_and_beyond_its_range_eq26() {
    let text = rose_world("range = 10", "", "whisker_length = 0");
    let mut w = world(&text, 1, 3);
    // d = θ exactly: eq. 26 requires d < θ.
    put(&mut w, 0, 110.0, 100.0, 0.0);
    w.step(&mut [Still]);
    assert_eq!(w.creatures()[0].smell[0][0], 0.0, "at d = θ");
    put(&mut w, 0, 125.0, 100.0, 0.0);
    w.step(&mut [Still]);
    assert_eq!(w.creatures()[0].smell[0][0], 0.0, "beyond θ");
    // Just inside: d = 9.5, I = 0.8 / (1 + 0.01 * 90.25).
    put(&mut w, 0, 109.5, 100.0, 0.0);
    w.step(&mut [Still]);
    assert_close(w.creatures()[0].smell[0][0], 0.8 / 1.9025, "inside θ");
}

#[test]
fn opaque_wall_hides_the_smell_and_a_transparent_one_does_not() {
    let wall = |opaque: bool| {
        format!("[[world.walls]]\nfrom = [105, 90]\nto = [105, 110]\nopaque = {opaque}")
    };
    for (opaque, want) in [(true, 0.0), (false, 0.4)] {
        let mut w = world(&rose_world("", &wall(opaque), "whisker_length = 0"), 1, 4);
        put(&mut w, 0, 110.0, 100.0, 0.0);
        w.step(&mut [Still]);
        assert_close(
            w.creatures()[0].smell[0][0],
            want,
            &format!("opaque = {opaque}"),
        );
    }
}

#[test]
fn receptors_saturate_at_one_and_sum_over_things() {
    // Intensity 5 at d = 10: I = 2.5, so receptor 1 = min(1, 2.5) = 1 and receptor 8 =
    // min(1, 1.25) = 1, while a weak component 0.1 gives 0.25.
    let text = rose_world("", "", "whisker_length = 0")
        .replace("intensity = 0.8", "intensity = 5")
        .replace("0, 0, 0, 0, 0, 0, 0.5]", "0.1, 0, 0, 0, 0, 0, 0.5]");
    let mut w = world(&text, 1, 5);
    put(&mut w, 0, 110.0, 100.0, 0.0);
    w.step(&mut [Still]);
    let s = w.creatures()[0].smell[0];
    assert_eq!(s[0], 1.0);
    assert_eq!(s[7], 1.0);
    assert_close(s[1], 0.25, "weak component");

    // Two roses 10 LU away on either side: 0.4 + 0.4.
    let second = "[[world.objects]]\nkind = \"rose\"\nposition = [120, 100]";
    let mut w = world(&rose_world("", second, "whisker_length = 0"), 1, 6);
    put(&mut w, 0, 110.0, 100.0, 0.0);
    w.step(&mut [Still]);
    assert_close(w.creatures()[0].smell[0][0], 0.8, "two sources add up");
}

#[test]
fn whisker_contact_inhibits_smell_when_asked() {
    // A transparent wall at x = 7; facing -x from (10.2, 100) the whisker tips reach
    // x = 10.2 - 5 cos 45° = 6.66, across the wall. The rose is at (60, 100), on this side.
    let wall = "[[world.walls]]\nfrom = [7, 50]\nto = [7, 150]\nopaque = false";
    let text = |inhibit: bool| {
        rose_world("", wall, &format!("inhibit_smell_on_whisker = {inhibit}"))
            .replace("position = [100, 100]", "position = [60, 100]")
    };
    let mut plain = world(&text(false), 1, 7);
    let mut inhibited = world(&text(true), 1, 7);
    for w in [&mut plain, &mut inhibited] {
        put(w, 0, 10.2, 100.0, 180.0);
        w.step(&mut [Still]);
        assert_eq!(w.creatures()[0].whiskers, [true, true]);
    }
    assert!(plain.creatures()[0].smell[0][0] > 0.0);
    assert!(plain.creatures()[0].smell[1][0] > 0.0);
    assert_eq!(inhibited.creatures()[0].smell, [[0.0; 8]; 2]);
    assert_eq!(inhibited.observation(0)[..16], [0.0; 16]);

    // Turned round, the whiskers are free and the smell comes back.
    put(&mut inhibited, 0, 10.2, 100.0, 0.0);
    inhibited.step(&mut [Still]);
    assert_eq!(inhibited.creatures()[0].whiskers, [false, false]);
    assert!(inhibited.creatures()[0].smell[0][0] > 0.0);
}

#[test]
fn smell_following_the_amount_halves_when_half_eaten() {
    // Honey holds 2 units of A, a bite takes 1. Creature 0 sits on it and eats; creature 1,
    // 10 LU away, smells it after creature 0's turn in the same tick (§9 order).
    let text = rose_world(
        "substance = [2, 0, 0, 0]\nbite = [1, 0, 0, 0]\nsmell_follows_amount = true",
        "",
        "whisker_length = 0",
    );
    let mut w = world(&text, 2, 8);
    put(&mut w, 0, 100.0, 100.0, 0.0);
    put(&mut w, 1, 100.0, 110.0, 0.0);
    w.step(&mut [Still, Still]);
    // Creature 0 smelled the full honey at d = 0 (0.8) before eating half of it.
    assert_close(w.creatures()[0].smell[0][0], 0.8, "full honey at d = 0");
    assert_eq!(w.food()[0].amount[0], 1.0);
    assert_close(
        w.creatures()[1].smell[0][0],
        0.4 * 0.5,
        "half-eaten honey at d = 10",
    );
    w.step(&mut [Still, Still]);
    assert_close(w.creatures()[0].smell[0][0], 0.4, "half honey at d = 0");
    assert_eq!(w.creatures()[1].smell[0][0], 0.0, "eaten up");
}

#[test]
fn creatures_smell_each_other_but_not_themselves() {
    // Body odour ⟨0, 1, 0, …⟩ at intensity 0.5; the other creature 10 LU away gives
    // 0.5 / (1 + 1) = 0.25. Its own odour (d = 0, 0.5) must not be added.
    let text =
        "[creature]\nwhisker_length = 0\nodour = [0, 1, 0, 0, 0, 0, 0, 0]\nodour_intensity = 0.5";
    let mut w = world(text, 2, 9);
    put(&mut w, 0, 100.0, 100.0, 0.0);
    put(&mut w, 1, 110.0, 100.0, 0.0);
    w.step(&mut [Still, Still]);
    for i in 0..2 {
        assert_close(w.creatures()[i].smell[0][1], 0.25, "other creature's odour");
        assert_eq!(w.creatures()[i].smell[0][0], 0.0);
    }
    // A dead creature no longer smells.
    w.kill(1);
    w.step(&mut [Still, Still]);
    assert_eq!(w.creatures()[0].smell[0][1], 0.0);
}

#[test]
fn smell_is_only_computed_when_used_or_asked_for() {
    let text = rose_world(
        "",
        "",
        "whisker_length = 0\n[creature.inputs]\nsmell = false",
    );
    let mut w = world(&text, 1, 10);
    put(&mut w, 0, 110.0, 100.0, 0.0);
    assert_eq!(w.observation(0).len(), 2 + 4 + 1 + 1);
    w.step(&mut [Still]);
    assert_eq!(w.creatures()[0].smell[0][0], 0.0);
    w.set_full_sensing(true);
    w.step(&mut [Still]);
    assert_close(w.creatures()[0].smell[0][0], 0.4, "full sensing");
    assert_eq!(w.observation(0).len(), 8);
}
