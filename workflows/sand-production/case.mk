# Sand production (thesis §4.4): a 1 x 1 x 0.08 m slab of 37,120 bonded spheres under 18 MPa, a
# 0.18 m well drilled (phase 1), then produced with a 15 MPa drawdown (phase 2).
#   make -f Makefile.cases sand-production   the whole chain (README.md: its cost; the production
#                                            phases are long: about an hour each on two cores)
#   make -f Makefile.cases sand-production-drill   up to the drilled slab and its report (phase 1)
#   make -f Makefile.cases sand-production-speed-error   the small version's production at three
#                                            time steps and three void-fraction supports (speed_error.sh)
#   make -f Makefile.cases sand-production-speed-error-full   the same on the full case's drilled slab,
#                                            the production's first 3.4 ms (about 30 minutes)
SAND_DIR := $(OUT)/sand-production
SAND_CASE := workflows/sand-production
SAND_SCENE := $(SAND_CASE)/scene.toml
# The well's axis and radius, the far field and the bins of the report (inside the servo box).
SAND_WELL := --centre 0.5,0.5 --radius 0.09 --sigma0 18e6 --outer 0.48 --bin 0.02

$(SAND_DIR)/tile.h5: $(SAND_CASE)/tile.toml $(BIN)/gen-primary
	$(BIN)/gen-primary --scene $< --out $@
$(SAND_DIR)/settled.h5: $(SAND_CASE)/copy.toml $(SAND_DIR)/tile.h5 $(BIN)/copy-settle
	$(BIN)/copy-settle --scene $< --in $(SAND_DIR)/tile.h5 --out $@
$(SAND_DIR)/compacted.h5: $(SAND_CASE)/copy.toml $(SAND_DIR)/settled.h5 $(BIN)/compact
	$(BIN)/compact --scene $< --in $(SAND_DIR)/settled.h5 --out $@
$(SAND_DIR)/loaded.h5: $(SAND_SCENE) $(SAND_DIR)/compacted.h5 $(BIN)/run-stage
	$(BIN)/run-stage --scene $(SAND_SCENE) --stage load --in $(SAND_DIR)/compacted.h5 --out $@ --checkpoint-every 50000 --restart
$(SAND_DIR)/cemented.h5: $(SAND_SCENE) $(SAND_DIR)/loaded.h5 $(BIN)/run-stage
	$(BIN)/run-stage --scene $(SAND_SCENE) --stage cement --in $(SAND_DIR)/loaded.h5 --out $@
# Phase 1: VTK frames every 0.5 ms (velocity; displacement from the drilling).
$(SAND_DIR)/drilled.h5 $(SAND_DIR)/vtk/drill_particles.pvd &: $(SAND_SCENE) $(SAND_DIR)/cemented.h5 $(BIN)/run-stage
	$(BIN)/run-stage --scene $(SAND_SCENE) --stage drill --in $(SAND_DIR)/cemented.h5 --out $(SAND_DIR)/drilled.h5 \
	  --vtk $(SAND_DIR)/vtk --checkpoint-every 50000 --restart
$(SAND_DIR)/drilled.vtu: $(SAND_DIR)/drilled.h5 $(SAND_DIR)/cemented.h5 $(BIN)/post-macro
	$(BIN)/post-macro --in $(SAND_DIR)/drilled.h5 --reference $(SAND_DIR)/cemented.h5 --vtk $@
# Stress against Kirsch, broken bonds and radial displacement against radius after drilling.
SAND_DRILL_REPORT := $(foreach k,kirsch bonds displacement,$(SAND_DIR)/drilled_$(k).csv $(SAND_DIR)/drilled_$(k).png)
$(SAND_DRILL_REPORT) &: $(SAND_DIR)/drilled.vtu $(SAND_DIR)/cemented.h5 $(SAND_DIR)/drilled.h5 scripts/well_report.py scripts/post_table.py
	$(PYTHON) scripts/well_report.py --stress $< --bonds-made $(SAND_DIR)/cemented.h5 --bonds-now $(SAND_DIR)/drilled.h5 \
	  $(SAND_WELL) --prefix $(SAND_DIR)/drilled
# Phase 2, with the fluid and without it: VTK frames every tenth of the phase, the sink log.
$(SAND_DIR)/produced.h5 $(SAND_DIR)/produced.sink.csv $(SAND_DIR)/vtk/produce_particles.pvd &: $(SAND_SCENE) $(SAND_DIR)/drilled.h5 $(BIN)/run-stage
	$(BIN)/run-stage --scene $(SAND_SCENE) --stage produce --in $(SAND_DIR)/drilled.h5 --out $(SAND_DIR)/produced.h5 \
	  --vtk $(SAND_DIR)/vtk --checkpoint-every 50000 --restart
$(SAND_DIR)/dry.h5 $(SAND_DIR)/dry.sink.csv &: $(SAND_SCENE) $(SAND_DIR)/drilled.h5 $(BIN)/run-stage
	$(BIN)/run-stage --scene $(SAND_SCENE) --stage produce_dry --in $(SAND_DIR)/drilled.h5 --out $(SAND_DIR)/dry.h5 \
	  --checkpoint-every 50000 --restart
$(SAND_DIR)/produced.vtu: $(SAND_DIR)/produced.h5 $(SAND_DIR)/cemented.h5 $(BIN)/post-macro
	$(BIN)/post-macro --in $(SAND_DIR)/produced.h5 --reference $(SAND_DIR)/cemented.h5 --vtk $@
SAND_PRODUCE_REPORT := $(foreach k,kirsch bonds displacement,$(SAND_DIR)/produced_$(k).csv $(SAND_DIR)/produced_$(k).png)
$(SAND_PRODUCE_REPORT) &: $(SAND_DIR)/produced.vtu $(SAND_DIR)/cemented.h5 $(SAND_DIR)/produced.h5 scripts/well_report.py scripts/post_table.py
	$(PYTHON) scripts/well_report.py --stress $< --bonds-made $(SAND_DIR)/cemented.h5 --bonds-now $(SAND_DIR)/produced.h5 \
	  $(SAND_WELL) --prefix $(SAND_DIR)/produced
$(SAND_DIR)/produced_mass.png: $(SAND_DIR)/produced.sink.csv $(SAND_DIR)/dry.sink.csv scripts/plot_sink.py
	$(PYTHON) scripts/plot_sink.py $@ $(SAND_DIR)/produced.sink.csv $(SAND_DIR)/dry.sink.csv

.PHONY: sand-production sand-production-outputs sand-production-drill sand-production-drill-outputs sand-production-speed-error \
  sand-production-speed-error-full
sand-production-speed-error: build
	bash $(SAND_CASE)/speed_error.sh $(BUILD) $(SAND_DIR)/speed_error
sand-production-speed-error-full: build $(SAND_DIR)/drilled.h5 $(SAND_DIR)/cemented.h5
	bash $(SAND_CASE)/speed_error.sh $(BUILD) $(SAND_DIR)/speed_error_full full $(SAND_DIR)
sand-production: build
	@$(MAKE) --no-print-directory -f $(SELF) sand-production-outputs
	@echo "sand-production: VTK series $(SAND_DIR)/vtk/drill_particles.pvd, produce_particles.pvd (velocity, displacement)"
	@echo "sand-production: produced sand $(SAND_DIR)/produced.sink.csv, produced_mass.png; around the well $(SAND_DIR)/{drilled,produced}_{kirsch,bonds,displacement}.{csv,png}"
sand-production-outputs: $(SAND_DRILL_REPORT) $(SAND_PRODUCE_REPORT) $(SAND_DIR)/produced_mass.png
sand-production-drill: build
	@$(MAKE) --no-print-directory -f $(SELF) sand-production-drill-outputs
	@echo "sand-production-drill: $(SAND_DIR)/vtk/drill_particles.pvd; $(SAND_DIR)/drilled_{kirsch,bonds,displacement}.{csv,png}"
sand-production-drill-outputs: $(SAND_DRILL_REPORT)
CASES += sand-production
