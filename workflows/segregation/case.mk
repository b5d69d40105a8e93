# Brazil-nut segregation (thesis §4.5): the README's demo.
#   make -f Makefile.cases segregation        generate, settle, vibrate 94 cycles at 3 g (the thesis's
#                                             span) and, from the same bed, 150 at 5 g; post-process,
#                                             report and plot (about 8 minutes on 2 cores)
#   make -f Makefile.cases segregation-long   continue to 1,000 cycles and report the rise again
SEG_DIR := $(OUT)/segregation
SEG_SCENE := workflows/segregation/scene.toml
SEG_REPORT := $(PYTHON) scripts/segregation_report.py --intruder 0 --frequency 20

$(SEG_DIR)/settled.h5: $(SEG_SCENE) $(BIN)/gen-primary
	$(BIN)/gen-primary --scene $(SEG_SCENE) --out $@

# The large sphere (id 0) is tracked 45 times per cycle; one VTK frame per cycle at the same phase.
$(SEG_DIR)/vibrated.h5 $(SEG_DIR)/intruder.csv &: $(SEG_SCENE) $(SEG_DIR)/settled.h5 $(BIN)/run-stage
	$(BIN)/run-stage --scene $(SEG_SCENE) --stage vibrate --in $(SEG_DIR)/settled.h5 --out $(SEG_DIR)/vibrated.h5 \
	  --track $(SEG_DIR)/intruder.csv --track-ids 0 --track-every 100 --vtk $(SEG_DIR)/vtk \
	  --checkpoint-every 50000 --restart

# The same settled bed at 5 g (stage rise), where the large sphere reaches the surface.
$(SEG_DIR)/risen.h5 $(SEG_DIR)/intruder_rise.csv &: $(SEG_SCENE) $(SEG_DIR)/settled.h5 $(BIN)/run-stage
	$(BIN)/run-stage --scene $(SEG_SCENE) --stage rise --in $(SEG_DIR)/settled.h5 --out $(SEG_DIR)/risen.h5 \
	  --track $(SEG_DIR)/intruder_rise.csv --track-ids 0 --track-every 100 --vtk $(SEG_DIR)/vtk \
	  --checkpoint-every 50000 --restart

# Particles coloured by their displacement over the span, and the displacement field on an 8 mm grid
# (kernel width one small diameter): open in ParaView with the VTK series in vtk/.
$(SEG_DIR)/displacement.vtu $(SEG_DIR)/fields.vti &: $(SEG_DIR)/settled.h5 $(SEG_DIR)/vibrated.h5 $(BIN)/post-macro
	$(BIN)/post-macro --reference $(SEG_DIR)/settled.h5 --in $(SEG_DIR)/vibrated.h5 --vtk $(SEG_DIR)/displacement.vtu \
	  --grid $(SEG_DIR)/fields.vti --cell 0.008 --width 0.008

$(SEG_DIR)/segregation.png $(SEG_DIR)/summary.csv $(SEG_DIR)/convection.csv &: $(SEG_DIR)/settled.h5 $(SEG_DIR)/vibrated.h5 \
    $(SEG_DIR)/intruder.csv $(SEG_DIR)/intruder_rise.csv scripts/segregation_report.py scripts/post_table.py
	$(SEG_REPORT) --start $(SEG_DIR)/settled.h5 --span $(SEG_DIR)/vibrated.h5 --track $(SEG_DIR)/intruder.csv \
	  --rise-track $(SEG_DIR)/intruder_rise.csv --rise-gamma 5 --summary $(SEG_DIR)/summary.csv --convection $(SEG_DIR)/convection.csv --png $(SEG_DIR)/segregation.png

$(SEG_DIR)/long.h5 $(SEG_DIR)/intruder_long.csv &: $(SEG_SCENE) $(SEG_DIR)/vibrated.h5 $(BIN)/run-stage
	$(BIN)/run-stage --scene $(SEG_SCENE) --stage continue --in $(SEG_DIR)/vibrated.h5 --out $(SEG_DIR)/long.h5 \
	  --track $(SEG_DIR)/intruder_long.csv --track-ids 0 --track-every 100 --vtk $(SEG_DIR)/vtk \
	  --checkpoint-every 200000 --restart

$(SEG_DIR)/segregation_long.png $(SEG_DIR)/summary_long.csv $(SEG_DIR)/convection_long.csv &: $(SEG_DIR)/long.h5 \
    $(SEG_DIR)/intruder.csv $(SEG_DIR)/intruder_long.csv scripts/segregation_report.py scripts/post_table.py
	$(SEG_REPORT) --start $(SEG_DIR)/settled.h5 --span $(SEG_DIR)/vibrated.h5 --end $(SEG_DIR)/long.h5 \
	  --track $(SEG_DIR)/intruder.csv $(SEG_DIR)/intruder_long.csv \
	  --summary $(SEG_DIR)/summary_long.csv --convection $(SEG_DIR)/convection_long.csv --png $(SEG_DIR)/segregation_long.png

.PHONY: segregation segregation-outputs segregation-long segregation-long-outputs
segregation: build
	@$(MAKE) --no-print-directory -f $(SELF) segregation-outputs
	@echo "segregation: VTK series $(SEG_DIR)/vtk/vibrate_particles.pvd and rise_particles.pvd (walls: vibrate_walls.pvd), displacement $(SEG_DIR)/displacement.vtu, fields $(SEG_DIR)/fields.vti"
	@echo "segregation: plot $(SEG_DIR)/segregation.png, figures $(SEG_DIR)/summary.csv, convection profile $(SEG_DIR)/convection.csv"
segregation-outputs: $(SEG_DIR)/segregation.png $(SEG_DIR)/displacement.vtu
segregation-long: build
	@$(MAKE) --no-print-directory -f $(SELF) segregation-long-outputs
	@echo "segregation-long: plot $(SEG_DIR)/segregation_long.png, figures $(SEG_DIR)/summary_long.csv"
segregation-long-outputs: $(SEG_DIR)/segregation_long.png
CASES += segregation

# Rise against the shaking (workflows/segregation/sweep.toml, automatic time step): 600 cycles at
# 3, 4 and 5 g (20 Hz) and at 3 g (10 Hz) from one settled bed; about 20 minutes on one core.
#   make -f Makefile.cases segregation-sweep
SEG_SWEEP := workflows/segregation/sweep.toml
SEG_SWEEP_DIR := $(SEG_DIR)/sweep
SEG_SWEEP_RUNS := g3:20:3 g4:20:4 g5:20:5 g3_10hz:10:3# stage:frequency [Hz]:peak acceleration [g]
seg_sweep_word = $(word $(2),$(subst :, ,$(1)))
seg_sweep_run = --run $(call seg_sweep_word,$(1),1) $(SEG_SWEEP_DIR)/$(call seg_sweep_word,$(1),1).csv \
  $(call seg_sweep_word,$(1),2) $(call seg_sweep_word,$(1),3)

$(SEG_SWEEP_DIR)/settled.h5: $(SEG_SWEEP) $(BIN)/gen-primary
	$(BIN)/gen-primary --scene $(SEG_SWEEP) --out $@

$(SEG_SWEEP_DIR)/%.h5 $(SEG_SWEEP_DIR)/%.csv: $(SEG_SWEEP) $(SEG_SWEEP_DIR)/settled.h5 $(BIN)/run-stage
	$(BIN)/run-stage --scene $(SEG_SWEEP) --stage $* --in $(SEG_SWEEP_DIR)/settled.h5 --out $(SEG_SWEEP_DIR)/$*.h5 \
	  --track $(SEG_SWEEP_DIR)/$*.csv --track-ids 0 --track-every 100 --checkpoint-every 200000 --restart

$(SEG_SWEEP_DIR)/sweep.csv $(SEG_SWEEP_DIR)/sweep.png &: $(SEG_SWEEP_DIR)/settled.h5 \
    $(foreach r,$(SEG_SWEEP_RUNS),$(SEG_SWEEP_DIR)/$(call seg_sweep_word,$(r),1).h5) \
    scripts/segregation_sweep.py scripts/segregation_report.py scripts/post_table.py
	$(PYTHON) scripts/segregation_sweep.py --start $(SEG_SWEEP_DIR)/settled.h5 \
	  $(foreach r,$(SEG_SWEEP_RUNS),$(call seg_sweep_run,$(r))) --table $(SEG_SWEEP_DIR)/sweep.csv --png $(SEG_SWEEP_DIR)/sweep.png

.PHONY: segregation-sweep segregation-sweep-outputs
segregation-sweep: build
	@$(MAKE) --no-print-directory -f $(SELF) segregation-sweep-outputs
	@echo "segregation-sweep: table $(SEG_SWEEP_DIR)/sweep.csv, plot $(SEG_SWEEP_DIR)/sweep.png"
segregation-sweep-outputs: $(SEG_SWEEP_DIR)/sweep.csv

# Rise over several fills (workflows/segregation/seeds.toml): fills that differ only in the
# generation seed (SEG_SEEDS), each shaken at 3 g and 20 Hz for 700 cycles at the thesis's step
# under a lid at 0.12 m; about 15 minutes per fill on one core (make -j2 runs two fills at once).
#   make -f Makefile.cases segregation-seeds [SEG_SEEDS="1 2 3"]
SEG_SEEDS_SCENE := workflows/segregation/seeds.toml
SEG_SEEDS_DIR := $(SEG_DIR)/seeds
SEG_SEEDS ?= 2004 1 2 3 4 5 6 7# 2004: the demo's own fill (scene.toml)

# One copy of scene.toml per seed, so that each fill's checkpoint records the scene that made it.
$(SEG_SEEDS_DIR)/fill_%.toml: $(SEG_SCENE)
	@mkdir -p $(@D)
	sed 's/^seed = 2004$$/seed = $*/' $< > $@.tmp && grep -q '^seed = $*$$' $@.tmp && mv $@.tmp $@

.SECONDARY: $(foreach s,$(SEG_SEEDS),$(SEG_SEEDS_DIR)/fill_$(s).toml $(SEG_SEEDS_DIR)/fill_$(s).h5)
$(SEG_SEEDS_DIR)/fill_%.h5: $(SEG_SEEDS_DIR)/fill_%.toml $(BIN)/gen-primary
	$(BIN)/gen-primary --scene $< --out $@ --quiet

$(SEG_SEEDS_DIR)/shake_%.h5 $(SEG_SEEDS_DIR)/shake_%.csv &: $(SEG_SEEDS_SCENE) $(SEG_SEEDS_DIR)/fill_%.h5 $(BIN)/run-stage
	OMP_NUM_THREADS=1 $(BIN)/run-stage --scene $(SEG_SEEDS_SCENE) --stage shake --in $(SEG_SEEDS_DIR)/fill_$*.h5 \
	  --out $(SEG_SEEDS_DIR)/shake_$*.h5 --track $(SEG_SEEDS_DIR)/shake_$*.csv --track-ids 0 --track-every 100 \
	  --checkpoint-every 500000 --restart --quiet

$(SEG_SEEDS_DIR)/seeds.csv $(SEG_SEEDS_DIR)/spread.csv $(SEG_SEEDS_DIR)/seeds.png &: \
    $(foreach s,$(SEG_SEEDS),$(SEG_SEEDS_DIR)/shake_$(s).h5) scripts/segregation_sweep.py scripts/segregation_report.py scripts/post_table.py
	$(PYTHON) scripts/segregation_sweep.py $(foreach s,$(SEG_SEEDS),--start $(SEG_SEEDS_DIR)/fill_$(s).h5) \
	  $(foreach s,$(SEG_SEEDS),--run seed_$(s) $(SEG_SEEDS_DIR)/shake_$(s).csv 20 3) \
	  --table $(SEG_SEEDS_DIR)/seeds.csv --summary $(SEG_SEEDS_DIR)/spread.csv --png $(SEG_SEEDS_DIR)/seeds.png \
	  --title "Brazil-nut rise at 3 g, 20 Hz, from $(words $(SEG_SEEDS)) fills (lid at 0.12 m)"

.PHONY: segregation-seeds segregation-seeds-outputs
segregation-seeds: build
	@$(MAKE) --no-print-directory -f $(SELF) segregation-seeds-outputs
	@echo "segregation-seeds: table $(SEG_SEEDS_DIR)/seeds.csv, spread $(SEG_SEEDS_DIR)/spread.csv, plot $(SEG_SEEDS_DIR)/seeds.png"
segregation-seeds-outputs: $(SEG_SEEDS_DIR)/seeds.png
