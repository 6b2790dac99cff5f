// Parameters of sectoral_ism, configuration cone12: sectoral_ism #(`SECTORAL_ISM_CONE12_PARAMS) u (...);
`define SECTORAL_ISM_CONE12_PARAMS \
  .READING_W(16), \
  .RINGS(25), \
  .BINS(12), \
  .SECTORS(3), \
  .CLASSES(5), \
  .WINDOW(11), \
  .IDX_W(6), \
  .READING_FRAC(8), \
  .LOG_FRAC(8), \
  .QUAD_SHIFT(24), \
  .LOG_W(19), \
  .COEF_W(18), \
  .NORM_W(11), \
  .WEIGHT_W(13), \
  .PHI_N(2440), \
  .PHI_W(8), \
  .THR_W(14), \
  .BUCKET_SHIFT(8), \
  .BUCKET_N(38), \
  .QUAD_COEF_FILE("config/cone12/sectoral_ism_cone12_quad_coef.mem"), \
  .LOG_NORM_FILE("config/cone12/sectoral_ism_cone12_log_norm.mem"), \
  .LOG_WEIGHT_FILE("config/cone12/sectoral_ism_cone12_log_weight.mem"), \
  .LOG_ADD_FILE("config/cone12/sectoral_ism_cone12_log_add.mem"), \
  .THRESHOLDS_FILE("config/cone12/sectoral_ism_cone12_thresholds.mem"), \
  .THRESHOLD_BUCKET_FILE("config/cone12/sectoral_ism_cone12_threshold_bucket.mem")
