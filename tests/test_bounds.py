"""Shortest paths and assignment bounds, on hand-checked cases and the MovingAI figures."""

from __future__ import annotations

import math

import numpy as np
from helpers import EXAMPLES

from asprilo.bounds import Floor, bottleneck_assignment, mapf_bounds, min_cost_assignment
from asprilo.model import Robot
from asprilo.reader import read_instance


def test_distances_around_a_wall():
    # 3x3 floor without its centre: going from (1,2) to (3,2) takes 4 steps
    floor = Floor({(x, y) for x in range(1, 4) for y in range(1, 4)} - {(2, 2)})
    assert floor.distances([(1, 2)], [(3, 2), (1, 2), (2, 2)]).tolist() == [[4, 0, math.inf]]


def test_assignments():
    costs = np.array([[1, 5, 9], [2, 3, 8]], dtype=float)
    assert bottleneck_assignment(costs) == 3  # goal 0 <- robot 0 (1), goal 1 <- robot 1 (3)
    assert min_cost_assignment(costs) == 4
    assert bottleneck_assignment(np.array([[math.inf, math.inf]])) == math.inf
    assert min_cost_assignment(np.zeros((2, 1))) == math.inf


def test_m_bounds_of_a_paper_instance():
    instance = read_instance(EXAMPLES / "paper-m/1x2x4/x11_y6_n66_r2_s16_ps1_pr16_u16_o2_N001.lp")
    # robots at (1,6) and (2,6); ordered shelves at (5,3) and (3,3) on a full grid:
    # (1,6)->(3,3) = 5 and (2,6)->(5,3) = 6 beats (1,6)->(5,3) = 7 and (2,6)->(3,3) = 4
    assert mapf_bounds(instance) == (6.0, 11.0)


def test_md_bounds_count_each_destination_once():
    instance = read_instance(EXAMPLES / "encodings-repo/x3_y3_n9_r1_s1_ps1_pr1_u1_o1_N1.lp")
    instance.orders.clear()
    instance.robots = {1: Robot(1, (1, 1)), 2: Robot(2, (3, 3))}
    from asprilo.model import Destination
    instance.destinations = {1: Destination(1, (2, 1)), 2: Destination(2, (3, 2))}
    assert mapf_bounds(instance) == (1.0, 2.0)
