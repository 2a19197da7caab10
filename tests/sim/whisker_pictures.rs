//! Whiskers (§7.3) drawn as pictures: a 13 x 13 LU neighbourhood of the creature, one
//! character per integer point, with the 0/1 readings asserted next to each picture.
//!
//! Legend: `L`/`R` left/right whisker tip (nearest point), `#` a wall within 0.5 LU,
//! `a` aversive object, `f` food, `c` another creature's body, `O` the creature's own body,
//! `.` nothing. Earlier symbols win where they overlap.

use crate::sim_common::{put, world, Still};
use berry_evolve::geometry::{point_segment_distance_squared, Vec2};
use berry_evolve::sim::World;

/// The picture around creature 0, centred on the integer point nearest its centre.
fn picture(w: &World) -> String {
    let me = &w.creatures()[0];
    let centre = me.pose.position.round();
    let tips = w.whisker_tips(0).map(|t| t.round());
    let r = w.creature_radius();
    let mut rows = Vec::new();
    for dy in -6..=6 {
        let mut row = String::new();
        for dx in -6..=6 {
            let p = centre + Vec2::new(dx as f64, dy as f64);
            let near = |q: Vec2, radius: f64| p.distance(q) <= radius.max(0.5);
            let ch = if p == tips[0] {
                'L'
            } else if p == tips[1] {
                'R'
            } else if w
                .wall_segments()
                .iter()
                .any(|s| point_segment_distance_squared(p, s) <= 0.25)
            {
                '#'
            } else if w.aversives().iter().any(|a| near(a.position, a.radius)) {
                'a'
            } else if w.food().iter().any(|f| near(f.position, f.radius)) {
                'f'
            } else if w.creatures()[1..]
                .iter()
                .any(|c| p.distance(c.pose.position) <= r)
            {
                'c'
            } else if p.distance(me.pose.position) <= r {
                'O'
            } else {
                '.'
            };
            row.push(ch);
        }
        rows.push(row);
    }
    rows.join("\n")
}

/// One still tick, then the picture and the whisker readings of creature 0.
fn look(w: &mut World) -> (String, [bool; 2]) {
    let mut controllers = vec![Still; w.creatures().len()];
    w.step(&mut controllers);
    let obs = w.observation(0);
    // Default layout: 16 smell inputs, then the two whiskers.
    let readings = [obs[16] == 1.0, obs[17] == 1.0];
    assert_eq!(
        readings,
        w.creatures()[0].whiskers,
        "observation vs creature"
    );
    (picture(w), readings)
}

fn wall_world(from: [f64; 2], to: [f64; 2]) -> World {
    let text = format!(
        "[[world.walls]]\nfrom = [{}, {}]\nto = [{}, {}]\n",
        from[0], from[1], to[0], to[1]
    );
    // Start somewhere else; each test puts the creature where it wants it.
    world(
        &format!("{text}[world.start]\nregion = [200, 200, 200, 200]"),
        1,
        1,
    )
}

#[test]
fn whiskers_stop_short_of_a_wall() {
    // Facing +x at (10, 10): tips at x = 10 + 5 cos 45° = 13.54, the wall at x = 14.
    let mut w = wall_world([14.0, 0.0], [14.0, 30.0]);
    put(&mut w, 0, 10.0, 10.0, 0.0);
    let (pic, readings) = look(&mut w);
    let want = "\
..........#..
..........#..
..........L..
......O...#..
....OOOOO.#..
....OOOOO.#..
...OOOOOOO#..
....OOOOO.#..
....OOOOO.#..
......O...#..
..........R..
..........#..
..........#..";
    assert_eq!(pic, want, "\n{pic}");
    assert_eq!(readings, [false, false]);
}

#[test]
fn both_whiskers_cross_a_wall_ahead() {
    // The wall at x = 13.4: both tips (x = 13.54) lie beyond it; the body (edge at 13) does
    // not touch it.
    let mut w = wall_world([13.4, 0.0], [13.4, 30.0]);
    put(&mut w, 0, 10.0, 10.0, 0.0);
    let (pic, readings) = look(&mut w);
    let want = "\
.........#...
.........#...
.........#L..
......O..#...
....OOOOO#...
....OOOOO#...
...OOOOOO#...
....OOOOO#...
....OOOOO#...
......O..#...
.........#R..
.........#...
.........#...";
    assert_eq!(pic, want, "\n{pic}");
    assert_eq!(readings, [true, true]);
}

#[test]
fn only_the_left_whisker_feels_a_wall_on_the_left() {
    // Facing +x, left is up the screen (y smaller). The wall at y = 6.8 crosses the left
    // whisker (tip y = 6.46) and misses the body (top at y = 7).
    let mut w = wall_world([0.0, 6.8], [30.0, 6.8]);
    put(&mut w, 0, 10.0, 10.0, 0.0);
    let (pic, readings) = look(&mut w);
    let want = "\
.............
.............
..........L..
#############
....OOOOO....
....OOOOO....
...OOOOOOO...
....OOOOO....
....OOOOO....
......O......
..........R..
.............
.............";
    assert_eq!(pic, want, "\n{pic}");
    assert_eq!(readings, [true, false]);
}

#[test]
fn facing_up_the_left_whisker_points_up_left() {
    // Heading -y (270°): the left tip is at (6.46, 6.46), the right at (13.54, 6.46). A wall
    // at x = 6.6 is crossed by the left whisker only.
    let mut w = wall_world([6.6, 0.0], [6.6, 30.0]);
    put(&mut w, 0, 10.0, 10.0, 270.0);
    let (pic, readings) = look(&mut w);
    let want = "\
...#.........
...#.........
..L#......R..
...#..O......
...#OOOOO....
...#OOOOO....
...#OOOOOO...
...#OOOOO....
...#OOOOO....
...#..O......
...#.........
...#.........
...#.........";
    assert_eq!(pic, want, "\n{pic}");
    assert_eq!(readings, [true, false]);
}

#[test]
fn whiskers_feel_circles_but_not_points() {
    // An aversive disc of radius 1 at (14, 13) is crossed by the right whisker (its tip is
    // 0.71 LU from the centre). Point food at (12, 8) lies on the left whisker but has radius
    // 0, so it is not felt (it is under the body, so the food detector reacts).
    let text = r#"
[world.kinds.thorn]
class = "aversive"
radius = 1

[world.kinds.seed]
class = "food"

[[world.objects]]
kind = "thorn"
position = [14, 13]

[[world.objects]]
kind = "seed"
position = [12, 8]

[world.start]
region = [200, 200, 200, 200]
"#;
    let mut w = world(text, 1, 2);
    put(&mut w, 0, 10.0, 10.0, 0.0);
    let (pic, readings) = look(&mut w);
    let want = "\
.............
.............
..........L..
......O......
....OOOOf....
....OOOOO....
...OOOOOOO...
....OOOOO....
....OOOOO.a..
......O..aaa.
..........R..
.............
.............";
    assert_eq!(pic, want, "\n{pic}");
    assert_eq!(readings, [false, true]);
    assert_eq!(w.creatures()[0].food_detectors, [true, false, false, false]);
}

#[test]
fn whiskers_feel_other_creatures_but_not_their_own_body() {
    // Creature 1 at (16, 6): the left tip (13.54, 6.46) is 2.5 LU from its centre, inside
    // its body. The bodies are 7.2 LU apart, not touching.
    let mut w = world("[world.start]\nregion = [100, 100, 200, 200]", 2, 3);
    put(&mut w, 0, 10.0, 10.0, 0.0);
    put(&mut w, 1, 16.0, 6.0, 180.0);
    let (pic, readings) = look(&mut w);
    let want = "\
..........ccc
..........ccc
.........cLcc
......O...ccc
....OOOOO.ccc
....OOOOO...c
...OOOOOOO...
....OOOOO....
....OOOOO....
......O......
..........R..
.............
.............";
    assert_eq!(pic, want, "\n{pic}");
    assert_eq!(readings, [true, false]);
    // Creature 1 faces -x from (16, 6), so its left is +y (down the screen): its left tip at
    // (12.46, 9.54) lies inside creature 0's body; its right tip (12.46, 2.46) touches nothing.
    assert_eq!(w.creatures()[1].whiskers, [true, false]);
}
