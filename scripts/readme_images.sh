#!/usr/bin/env bash
echo "usage: placeholder"
