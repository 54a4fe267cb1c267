"""The names in the statistics file that `flotsam stats` writes, for the scripts that read it.

formats/stats_file.hpp is the schema (types, dimensions, units, long names); this module
holds the same names, and tests/stats_file_test.cpp checks that the two lists agree.
"""

KIND = "stats"  # the global attribute flotsam_file_kind

# The groups (one body with one model variant), parameter sets, sections and regions.
GROUP_BODY = "group_body"
GROUP_VARIANT = "group_variant"
GROUP_MEMBERS = "group_members"
PARAM_SET_LABEL = "param_set_label"
PARAM_SET_IS_CONTROL = "param_set_is_control"
PARAM_MEMBERS = "param_members"
SECTION_NAME = "section_name"
SECTION_X = "section_x"
SECTION_Y_MIN = "section_y_min"
SECTION_Y_MAX = "section_y_max"
REGION_NAME = "region_name"

# First passages per (group, section); the same with BY_PARAM appended per (group,
# param_set, section).
PASSAGE_COUNT = "passage_count"
PASSAGE_Y_MEAN = "passage_y_mean"
PASSAGE_Y_MEDIAN = "passage_y_median"
PASSAGE_Y_STD = "passage_y_std"
PASSAGE_SPEED_MEAN = "passage_speed_mean"
PASSAGE_SPEED_MEDIAN = "passage_speed_median"
PASSAGE_SPEED_STD = "passage_speed_std"
PASSAGE_SPEED_BANDWIDTH = "passage_speed_bandwidth"
PASSAGE_SPEED_KDE = "passage_speed_kde"
BY_PARAM = "_by_param"
PASSAGE = (PASSAGE_COUNT, PASSAGE_Y_MEAN, PASSAGE_Y_MEDIAN, PASSAGE_Y_STD, PASSAGE_SPEED_MEAN, PASSAGE_SPEED_MEDIAN,
           PASSAGE_SPEED_STD, PASSAGE_SPEED_BANDWIDTH, PASSAGE_SPEED_KDE)
SPEED = "speed"
MEMBER_PASSAGE_TIME = "member_passage_time"
MEMBER_PASSAGE_Y = "member_passage_y"
MEMBER_PASSAGE_SPEED = "member_passage_speed"

# Yaw histograms after motion starts.
YAW_BIN = "yaw_bin"
YAW_BIN_BOUNDS = "yaw_bin_bounds"
MAX_ROTATION_HISTOGRAM = "max_rotation_histogram"
MAX_YAW_TO_MOTION_HISTOGRAM = "max_yaw_to_motion_histogram"

# Per member.
MEMBER_ID = "member_id"
MEMBER_GROUP = "member_group"
MEMBER_PARAM_SET = "member_param_set"
MEMBER_FLOW = "member_flow"
MEMBER_MOTION_START = "member_motion_start"
MEMBER_MAX_ROTATION = "member_max_rotation"
MEMBER_MAX_YAW_TO_MOTION = "member_max_yaw_to_motion"
MEMBER_MOTION_DIRECTION = "member_motion_direction"

# The paper's Fig. 16, from the run's start.
MEMBER_MAX_ROTATION_FROM_START = "member_max_rotation_from_start"
MEMBER_MOVEMENT_DIRECTION = "member_movement_direction"
MAX_ROTATION_FROM_START_HISTOGRAM = "max_rotation_from_start_histogram"
MAX_ROTATION_FROM_START_COUNT = "max_rotation_from_start_count"
MAX_ROTATION_FROM_START_MEDIAN = "max_rotation_from_start_median"
MAX_ROTATION_FROM_START_MEAN = "max_rotation_from_start_mean"
MAX_ROTATION_FROM_START_MIN = "max_rotation_from_start_min"
MAX_ROTATION_FROM_START_MAX = "max_rotation_from_start_max"
ROTATION_DIRECTION_CORRELATION = "rotation_direction_correlation"

# Regions at the arrival time.
MEMBER_REGION = "member_region"
REGION_COUNT = "region_count"
REGION_COUNT_BY_PARAM = "region_count_by_param"

# Distance from the start and R(t).
TIME = "time"
DISTANCE_MEAN = "distance_mean"
DISTANCE_STD = "distance_std"
RELATIVE_ERROR = "relative_error"

# Impacts on the scene's buildings, per (group, building) and, with ALL appended, per building.
BUILDING_ID = "building_id"
BUILDING_HIT_PROBABILITY = "building_hit_probability"
BUILDING_FIRST_HIT_TIME = "building_first_hit_time"
BUILDING_IMPACT_COUNT = "building_impact_count"
BUILDING_IMPACT_SPEED_MEDIAN = "building_impact_speed_median"
BUILDING_IMPACT_SPEED_P90 = "building_impact_speed_p90"
BUILDING_IMPACT_SPEED_MAX = "building_impact_speed_max"
BUILDING_IMPACT_FORCE_MEDIAN = "building_impact_force_median"
BUILDING_IMPACT_FORCE_P90 = "building_impact_force_p90"
BUILDING_IMPACT_FORCE_MAX = "building_impact_force_max"
ALL = "_all"
BUILDING = (BUILDING_HIT_PROBABILITY, BUILDING_FIRST_HIT_TIME, BUILDING_IMPACT_COUNT, BUILDING_IMPACT_SPEED_MEDIAN,
            BUILDING_IMPACT_SPEED_P90, BUILDING_IMPACT_SPEED_MAX, BUILDING_IMPACT_FORCE_MEDIAN, BUILDING_IMPACT_FORCE_P90,
            BUILDING_IMPACT_FORCE_MAX)

# The maps, over (group, y, x) and (y, x).
X = "x"
Y = "y"
PASS_PROBABILITY = "pass_probability"
MAX_DEBRIS_SPEED = "max_debris_speed"
PASS_PROBABILITY_ALL = "pass_probability_all"
MAX_DEBRIS_SPEED_ALL = "max_debris_speed_all"

# Every variable name, in the order of the file (without the grid mapping and the
# per-parameter param_set_<parameter> columns).
VARIABLES = (
    (GROUP_BODY, GROUP_VARIANT, GROUP_MEMBERS, PARAM_SET_LABEL, PARAM_SET_IS_CONTROL, PARAM_MEMBERS, SECTION_NAME,
     SECTION_X, SECTION_Y_MIN, SECTION_Y_MAX, REGION_NAME)
    + PASSAGE + tuple(name + BY_PARAM for name in PASSAGE)
    + (SPEED, MEMBER_PASSAGE_TIME, MEMBER_PASSAGE_Y, MEMBER_PASSAGE_SPEED,
       YAW_BIN, YAW_BIN_BOUNDS, MAX_ROTATION_HISTOGRAM, MAX_YAW_TO_MOTION_HISTOGRAM,
       MEMBER_ID, MEMBER_GROUP, MEMBER_PARAM_SET, MEMBER_FLOW,
       MEMBER_MOTION_START, MEMBER_MAX_ROTATION, MEMBER_MAX_YAW_TO_MOTION, MEMBER_MOTION_DIRECTION,
       MEMBER_MAX_ROTATION_FROM_START, MEMBER_MOVEMENT_DIRECTION, MAX_ROTATION_FROM_START_HISTOGRAM,
       MAX_ROTATION_FROM_START_COUNT, MAX_ROTATION_FROM_START_MEDIAN, MAX_ROTATION_FROM_START_MEAN,
       MAX_ROTATION_FROM_START_MIN, MAX_ROTATION_FROM_START_MAX, ROTATION_DIRECTION_CORRELATION,
       MEMBER_REGION, REGION_COUNT, REGION_COUNT_BY_PARAM,
       TIME, DISTANCE_MEAN, DISTANCE_STD, RELATIVE_ERROR, BUILDING_ID)
    + BUILDING + tuple(name + ALL for name in BUILDING)
    + (X, Y, PASS_PROBABILITY, MAX_DEBRIS_SPEED, PASS_PROBABILITY_ALL, MAX_DEBRIS_SPEED_ALL))

DIMENSIONS = ("group", "param_set", "section", "region", "speed", "yaw_bin", "bnds", "time", "member", "building", "x",
              "y")

# The global attributes (after Conventions and flotsam_file_kind); units in the names.
YAW_WINDOW = "yaw_window_s"
ARRIVAL_TIME = "arrival_time_s"
ATTRIBUTES = ("title", "source", "sweep_file", "scene_file", "scene_buildings_sha256", "history", YAW_WINDOW,
              "yaw_min_speed_m_s", "motion_threshold_m", ARRIVAL_TIME, "r_min_distance_m", "kde_bandwidth_rule",
              "kde_floor_m_s", "control_param_set", "map_coarsen")
